// Fuzz harness: the input reader of `deepcheck pd` (shapes, bodies and posed queries), then every
// query it accepts through DEEP and the exact reference (queries naming bodies: through the body
// depth). Bad input must end in an exception (the tool's one-line error), never a crash; an
// accepted query must give a finite signed distance and a unit normal (inputs are within deep's
// supported range once accepted).

#include "pd_input.h"

#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/signed_distance.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>

namespace {

/// Queries per input that are run (the reader itself sees them all).
constexpr std::size_t kMaxQueries = 8;

void requireSane(double distance, const Eigen::Vector3d& normal, const char* which) {
  if (std::isfinite(distance) && normal.allFinite() && std::abs(normal.norm() - 1.0) < 1e-6) return;
  std::fprintf(stderr, "%s: non-finite distance or non-unit normal (%g; %g %g %g)\n", which, distance, normal.x(),
               normal.y(), normal.z());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const deepcheck::tools::PdInput input = deepcheck::tools::readPdInput(in);
    for (std::size_t i = 0; i < input.queries.size() && i < kMaxQueries; ++i) {
      const deepcheck::tools::PdQuery& q = input.queries[i];
      if (q.namesBody()) {
        const auto r =
            deepcheck::geometry::bodySignedDistance(deepcheck::tools::queryBody(input, q.a, q.bodyA), q.X_WA,
                                                    deepcheck::tools::queryBody(input, q.b, q.bodyB), q.X_WB);
        requireSane(r.distance, r.normal, "bodySignedDistance");
        continue;
      }
      const auto& A = input.shapes[static_cast<std::size_t>(q.a)].hull;
      const auto& B = input.shapes[static_cast<std::size_t>(q.b)].hull;
      const auto r = deepcheck::geometry::signedDistance(A, q.X_WA, B, q.X_WB);
      requireSane(r.distance, r.normal, "signedDistance");
      const auto e = deepcheck::geometry::exactSignedDistance(A, q.X_WA, B, q.X_WB);
      requireSane(e.distance, e.normal, "exactSignedDistance");
    }
  } catch (const std::exception&) {
    // Rejected input: the tool prints the message and exits 1.
  }
  return 0;
}
