// The saved reproducers of DEEP's misses (tests/geometry/data/repro_pd_*.txt, `deepcheck pd` input
// format, written by bench/pd_bench): every query, cold and warm (one cache across the file's
// consecutive queries of a pair, as the tool runs them), exact and certified with the certified
// method.

#include "shapes.h"

#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/signed_distance.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck::geometry;
using namespace deepcheck::geometry::testing;
using Eigen::Isometry3d;
using Eigen::Vector3d;
namespace fs = std::filesystem;

namespace {

struct Case {
  std::vector<ConvexPolytope> shapes;
  struct Query {
    int a, b;
    Isometry3d X_WA, X_WB;
  };
  std::vector<Query> queries;
};

Isometry3d readPose(std::istringstream& in) {
  double t[3], q[4];
  in >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >> q[3];
  Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
  quat.normalize();
  Isometry3d X = Isometry3d::Identity();
  X.linear() = quat.toRotationMatrix();
  X.translation() = Vector3d(t[0], t[1], t[2]);
  return X;
}

/// Reads a file in the `deepcheck pd` input format (the reproducers are well formed).
Case readCase(const fs::path& path) {
  std::ifstream file(path);
  Case c;
  std::map<std::string, int> ids;
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string keyword;
    if (!(in >> keyword) || keyword[0] == '#') continue;
    if (keyword == "shape") {
      std::string id;
      int n = 0;
      in >> id >> n;
      std::vector<Vector3d> pts(static_cast<std::size_t>(n));
      for (Vector3d& p : pts) {
        std::getline(file, line);
        std::istringstream pin(line);
        pin >> p.x() >> p.y() >> p.z();
      }
      ids[id] = static_cast<int>(c.shapes.size());
      c.shapes.push_back(ConvexPolytope::fromPoints(pts));
    } else if (keyword == "query") {
      Case::Query q;
      std::string idA, idB;
      in >> idA;
      q.X_WA = readPose(in);
      in >> idB;
      q.X_WB = readPose(in);
      q.a = ids.at(idA);
      q.b = ids.at(idB);
      c.queries.push_back(q);
    }
  }
  return c;
}

std::vector<fs::path> savedReproducers() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(DEEPCHECK_SOURCE_DIR) / "tests/geometry/data"))
    if (e.path().filename().string().rfind("repro_pd_", 0) == 0) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(reproducers)

BOOST_AUTO_TEST_CASE(every_saved_deep_miss_is_exact_and_certified) {
  const std::vector<fs::path> files = savedReproducers();
  BOOST_TEST_REQUIRE(files.size() >= 50u);
  int queries = 0;
  for (const fs::path& path : files) {
    const Case c = readCase(path);
    BOOST_TEST_REQUIRE(!c.queries.empty(), path.filename());
    PairCache cache;
    int lastA = -1, lastB = -1;
    for (std::size_t i = 0; i < c.queries.size(); ++i) {
      const Case::Query& q = c.queries[i];
      const ConvexPolytope& A = c.shapes[static_cast<std::size_t>(q.a)];
      const ConvexPolytope& B = c.shapes[static_cast<std::size_t>(q.b)];
      if (q.a != lastA || q.b != lastB) cache.reset();
      lastA = q.a;
      lastB = q.b;
      const SignedDistanceResult warm = signedDistance(A, q.X_WA, B, q.X_WB, &cache);
      const SignedDistanceResult cold = signedDistance(A, q.X_WA, B, q.X_WB);
      const ExactResult exact = exactSignedDistance(A, q.X_WA, B, q.X_WB);
      const double L = depthScale(A, B);
      const double far = std::max(q.X_WA.translation().norm(), q.X_WB.translation().norm());
      const double tol = far > 1e3 ? 1e-10 : 1e-12;
      BOOST_TEST(depthError(cold.distance, exact.distance, L) <= tol,
                 path.filename() << " query " << i << ": cold " << cold.distance << " exact " << exact.distance);
      BOOST_TEST(depthError(warm.distance, exact.distance, L) <= tol,
                 path.filename() << " query " << i << ": warm " << warm.distance << " exact " << exact.distance);
      if (exact.distance < 0) {
        BOOST_TEST(cold.certified, path.filename() << " query " << i);
        BOOST_TEST(warm.certified, path.filename() << " query " << i);
      }
      ++queries;
    }
  }
  BOOST_TEST(queries >= 58);
}

BOOST_AUTO_TEST_SUITE_END()
