// Boost.Test entry point of the deepcheck::planners suite. OMPL's random seed is pinned here,
// before any OMPL object exists, so that every run of the suite draws the same samples.
#define BOOST_TEST_MODULE deepcheck_planners
#define BOOST_TEST_DYN_LINK
#include <boost/test/unit_test.hpp>

#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

namespace {

struct PinnedOmpl {
  PinnedOmpl() {
    ompl::RNG::setSeed(20240611);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  }
};

}  // namespace

BOOST_TEST_GLOBAL_FIXTURE(PinnedOmpl);
