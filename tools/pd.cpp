// `deepcheck pd`: signed distance / penetration depth of posed convex shapes read from stdin.
// The input and output formats are a contract, kept stable (tests/tool/test_pd.cpp checks them):
//
//   shape <id> <n>          followed by n lines "<x> <y> <z>": the shape is their convex hull
//   body <id> <shapeId> ... a body: the union of shapes given before, each in the body's frame
//   query <idA> <tx> <ty> <tz> <qw> <qx> <qy> <qz> <idB> <tx> <ty> <tz> <qw> <qx> <qy> <qz>
//                           idA and idB name shapes or bodies; a query naming a body is answered
//                           by geometry::bodySignedDistance (a shape there is a one-piece body)
//   # comment               (lines whose first non-blank character is '#'; blank lines too)
//
// Output: one line per query on stdout, "sd nx ny nz" with %.17g (sd > 0 distance, sd < 0 minus
// the penetration depth, n the unit normal from A towards B, world frame); on stderr a last line
// "queries N total_us T", T the time spent in the signed-distance calls only, in whole
// microseconds (parsing and hull building excluded).
//
// Values outside deep's supported range (deep/input_range.h: coordinates and translations up to
// 1e50 in magnitude, shapes spanning 0 or at least 1e-50) and shapes of more than
// kMaxShapePoints points are input errors.
//
// The whole input is parsed and every hull built before the first query runs, so a bad input
// produces no output on stdout, only one error line (naming the input line) and exit status 1.

#include "common.h"
#include "pd_input.h"
#include "subcommands.h"

#include "deepcheck/geometry/body_depth.h"
#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/signed_distance.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

using geometry::ConvexPolytope;

constexpr const char* kPdUsage =
    "usage: deepcheck pd [--cold] [--method certified|deep-walk|exact] < cases.txt\n"
    "\n"
    "Signed distance of pairs of posed convex shapes. Input on stdin:\n"
    "  shape <id> <n>      followed by n lines '<x> <y> <z>' (the shape is their convex hull)\n"
    "  body <id> <shapeId> <shapeId> ...   a body: the union of shapes given before, each in\n"
    "                      the body's frame\n"
    "  query <idA> <tx> <ty> <tz> <qw> <qx> <qy> <qz> <idB> <tx> <ty> <tz> <qw> <qx> <qy> <qz>\n"
    "                      idA, idB: shapes or bodies (a body's depth: the shortest translation\n"
    "                      of B after which no piece of A overlaps a piece of B)\n"
    "  lines starting with '#' are comments; blank lines are ignored.\n"
    "Supported range: |coordinate| and |translation| <= 1e50; a shape's points span 0 (one point)\n"
    "or at least 1e-50; at most 100000 points per shape.\n"
    "Output: one line 'sd nx ny nz' per query (sd < 0: penetration depth; n from A to B),\n"
    "and on stderr a last line 'queries N total_us T' (time in the queries only).\n"
    "\n"
    "options:\n"
    "  --cold    no warm start (by default consecutive queries of the same pair share a cache)\n"
    "  --method certified   (default) the certified penetration depth: an expanding surface\n"
    "                       of Minkowski vertices brackets the depth, DEEP's facets name it\n"
    "  --method deep-walk   DEEP's walks with restarts (the warm start reuses their basins)\n"
    "  --method exact       the exact brute-force reference (hull of all vertex differences)\n"
    "  --exact              same as --method exact\n";

int runPd(std::vector<std::string> args) {
  const bool cold = takeFlag(args, "--cold");
  const bool exactFlag = takeFlag(args, "--exact");
  const std::string method = takeSingleOption(args, "--method", exactFlag ? "exact" : "certified");
  if (method != "certified" && method != "deep-walk" && method != "exact")
    throw UsageError("unknown --method '" + method + "' (expected certified, deep-walk or exact)");
  if (exactFlag && method != "exact") throw UsageError("--exact contradicts --method " + method);
  const bool exact = method == "exact";
  geometry::PenetrationOptions options;
  options.method = method == "deep-walk" ? geometry::PenetrationMethod::GaussMapWalk
                                         : geometry::PenetrationMethod::CertifiedExpansion;
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args[0] + "' (input is read from stdin)");

  std::ios::sync_with_stdio(false);
  const PdInput input = readPdInput(std::cin);
  for (const PdQuery& q : input.queries) {
    if (exact && q.namesBody()) {
      throw InputError("line " + std::to_string(q.line) +
                       ": --method exact answers shape queries only; this query names a body");
    }
  }

  geometry::PairCache cache;
  geometry::PenetrationScratch scratch;  // the penetration methods' scratch, shared by every query
  cache.scratch = &scratch;
  int lastA = -1;
  int lastB = -1;
  std::chrono::steady_clock::duration total{0};
  for (const PdQuery& q : input.queries) {
    // Warm start only across consecutive queries of the same ordered pair of shapes.
    if (cold || q.namesBody() || q.a != lastA || q.b != lastB) cache.reset();
    lastA = q.a;
    lastB = q.b;
    double sd = 0.0;
    Eigen::Vector3d n;
    try {
      if (q.namesBody()) {
        const geometry::Body bodyA = queryBody(input, q.a, q.bodyA);
        const geometry::Body bodyB = queryBody(input, q.b, q.bodyB);
        geometry::BodyDepthOptions bodyOptions;
        bodyOptions.pair = options;
        const auto t0 = std::chrono::steady_clock::now();
        const geometry::BodySignedDistanceResult r =
            geometry::bodySignedDistance(bodyA, q.X_WA, bodyB, q.X_WB, bodyOptions);
        total += std::chrono::steady_clock::now() - t0;
        sd = r.distance;
        n = r.normal;
      } else if (exact) {
        const ConvexPolytope& A = input.shapes[static_cast<std::size_t>(q.a)].hull;
        const ConvexPolytope& B = input.shapes[static_cast<std::size_t>(q.b)].hull;
        const auto t0 = std::chrono::steady_clock::now();
        const geometry::ExactResult r = geometry::exactSignedDistance(A, q.X_WA, B, q.X_WB);
        total += std::chrono::steady_clock::now() - t0;
        sd = r.distance;
        n = r.normal;
      } else {
        const ConvexPolytope& A = input.shapes[static_cast<std::size_t>(q.a)].hull;
        const ConvexPolytope& B = input.shapes[static_cast<std::size_t>(q.b)].hull;
        const auto t0 = std::chrono::steady_clock::now();
        const geometry::SignedDistanceResult r = geometry::signedDistance(A, q.X_WA, B, q.X_WB, &cache, options);
        total += std::chrono::steady_clock::now() - t0;
        sd = r.distance;
        n = r.normal;
      }
    } catch (const std::exception& e) {
      std::fflush(stdout);
      throw InputError("query on line " + std::to_string(q.line) + ": " + e.what());
    }
    std::printf("%.17g %.17g %.17g %.17g\n", sd, n.x(), n.y(), n.z());
  }
  std::fflush(stdout);
  const long long micros =
      static_cast<long long>(std::llround(std::chrono::duration<double, std::micro>(total).count()));
  std::fprintf(stderr, "queries %zu total_us %lld\n", input.queries.size(), micros);
  return 0;
}

}  // namespace

const Subcommand kPdCommand = {"pd", "signed distance / penetration depth of posed convex shapes", kPdUsage, runPd};

}  // namespace deepcheck::tools
