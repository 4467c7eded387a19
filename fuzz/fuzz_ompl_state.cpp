// Fuzz harness: OMPL states of arbitrary values through the planners' validity checker
// (planners/validity_checker.h) on the bundled arm in the bundled shelf. The input is decoded into
// one value per variable; per variable a tag byte says how:
//   0      the next 8 bytes as a double (any bit pattern: NaN, infinities, denormals)
//   1..3   a point of [lower, upper] of that joint, from the next 2 bytes
//   4      a special value: NaN, infinities, zeros, the limits and the doubles just outside them...
//   5..7   the default value plus the next byte (signed) in thousandths
// (missing bytes: the default value). Every overload of isValid and clearance runs on the state;
// the push-out overload (many distance queries: slow) when the last byte is 1 modulo 16. A crash,
// a sanitizer report or an exception (but the one noted at the distance overloads) is a finding,
// as are: a state outside the limits or not finite called valid; a finite state within the limits
// with a clearance that is not finite; the two isValid overloads disagreeing; a pushed-out state
// that is not valid.

#include "harness_support.h"

#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/validity_checker.h"

#include <ompl/base/ScopedState.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace {

namespace planners = deepcheck::planners;

struct Setup {
  std::shared_ptr<ompl::geometric::SimpleSetup> ss;
  std::shared_ptr<const planners::StateValidityChecker> checker;
};

const Setup& setup() {
  static const Setup s = [] {
    const std::string data = DEEPCHECK_SOURCE_DIR "/robots/data";
    planners::SetupOptions options;
    options.packageRoots = {data};
    options.useRosPackagePath = false;
    options.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
    Setup out;
    out.ss = planners::makeSimpleSetup(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", {data + "/scenes/shelf.urdf"},
                                       options);
    out.checker = planners::validityCheckerOf(*out.ss);
    return out;
  }();
  return s;
}

/// Reads the input front to back; past its end every read gives nothing.
struct Bytes {
  const std::uint8_t* data;
  std::size_t size;
  bool take(void* out, std::size_t n) {
    if (size < n) return false;
    std::memcpy(out, data, n);
    data += n;
    size -= n;
    return true;
  }
};

double value(Bytes& in, double lower, double upper, double fallback) {
  std::uint8_t tag = 0;
  if (!in.take(&tag, 1)) return fallback;
  switch (tag % 8) {
    case 0: {
      double x = fallback;
      in.take(&x, sizeof x);
      return x;
    }
    case 1:
    case 2:
    case 3: {
      std::uint16_t u = 0;
      in.take(&u, sizeof u);
      return lower + (upper - lower) * (u / 65535.0);
    }
    case 4: {
      constexpr double inf = std::numeric_limits<double>::infinity();
      const double special[] = {std::numeric_limits<double>::quiet_NaN(),
                                -std::numeric_limits<double>::quiet_NaN(),
                                inf,
                                -inf,
                                0.0,
                                -0.0,
                                std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::lowest(),
                                lower,
                                upper,
                                std::nextafter(lower, -inf),
                                std::nextafter(upper, inf),
                                1e-300,
                                1e300,
                                std::numeric_limits<double>::epsilon()};
      std::uint8_t k = 0;
      in.take(&k, 1);
      return special[k % (sizeof special / sizeof special[0])];
    }
    default: {
      std::int8_t d = 0;
      in.take(&d, 1);
      return fallback + d / 1000.0;
    }
  }
}

void require(bool ok, const char* what) { deepcheck::fuzz::require(ok, "validity checker", what); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Setup& s = setup();
  const planners::StateValidityChecker& checker = *s.checker;
  const auto& robot = checker.world().robot();
  const int n = checker.dimension();
  const Eigen::VectorXd defaults = robot.defaultConfiguration();
  Eigen::VectorXd q(n);
  Bytes in{data, size};
  for (int i = 0; i < n; ++i) q[i] = value(in, robot.lowerLimits()[i], robot.upperLimits()[i], defaults[i]);

  ompl::base::ScopedState<> state(s.ss->getStateSpace());
  checker.mapping().toState(q, state.get());
  const bool inside = q.allFinite() && (q.array() >= robot.lowerLimits().array()).all() &&
                      (q.array() <= robot.upperLimits().array()).all();

  const bool valid = checker.isValid(state.get());
  require(inside || !valid, "a state outside the limits or not finite is valid");
  double dist = 0.0;
  const bool validWithDistance = checker.isValid(state.get(), dist);
  const double clearance = checker.clearance(state.get());
  if (!q.allFinite()) {
    require(dist == -std::numeric_limits<double>::infinity() && clearance == dist,
            "a state that is not finite has a clearance above -infinity");
  }
  require(valid == validWithDistance, "isValid(state) and isValid(state, dist) disagree");
  if (inside)
    require(std::isfinite(dist) && std::isfinite(clearance), "a state within the limits has no finite clearance");

  if (size > 0 && data[size - 1] % 16 == 1) {
    ompl::base::ScopedState<> pushed(s.ss->getStateSpace());
    bool available = false;
    double pushedDist = 0.0;
    const bool validAgain = checker.isValid(state.get(), pushedDist, pushed.get(), available);
    require(validAgain == valid, "the push-out overload of isValid disagrees");
    if (available) require(checker.isValid(pushed.get()), "the pushed-out state is not valid");
  }
  return 0;
}
