// The umbrella headers (<deepcheck/geometry.h>, robots.h, checker.h, planners.h) declare what an OMPL
// user needs: this file includes nothing else of deepcheck, plugs the validity checker and the
// motion validator into its own SimpleSetup through the Ptr aliases, and checks a motion.

#include <deepcheck/checker.h>
#include <deepcheck/geometry.h>
#include <deepcheck/planners.h>
#include <deepcheck/robots.h>

#include <boost/test/unit_test.hpp>

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>

#include <memory>
#include <string>
#include <type_traits>

namespace dp = deepcheck::planners;

static_assert(std::is_same_v<dp::StateValidityCheckerPtr, std::shared_ptr<dp::StateValidityChecker>>);
static_assert(std::is_same_v<dp::ClearanceMotionValidatorPtr, std::shared_ptr<dp::ClearanceMotionValidator>>);
static_assert(std::is_same_v<dp::LinkSpeedBoundPtr, std::shared_ptr<dp::LinkSpeedBound>>);
static_assert(std::is_same_v<dp::PushOutPtr, std::shared_ptr<dp::PushOut>>);

BOOST_AUTO_TEST_SUITE(planners_umbrella_headers)

BOOST_AUTO_TEST_CASE(an_ompl_setup_built_from_the_umbrella_headers_checks_states_and_motions) {
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  deepcheck::robots::LoadOptions load;
  load.packageRoots = {data};
  load.useRosPackagePath = false;
  deepcheck::checker::WorldOptions options;
  options.disabledPairs = deepcheck::robots::readSrdfDisabledPairs(data + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
  auto world = std::make_shared<deepcheck::checker::World>(
      deepcheck::robots::RobotModel::fromUrdfFile(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", load), options);
  world->addScene(deepcheck::robots::RobotModel::fromUrdfFile(data + "/scenes/shelf.urdf", load));

  // The suggested start of robots/data/README.md (free), and a motion of 0.3 rad of joint 1.
  Eigen::VectorXd qStart(7);
  qStart << 0, -0.4, 0, -1.6, 0, 1.2, 0;
  Eigen::VectorXd qEnd = qStart;
  qEnd[0] += 0.3;

  ompl::geometric::SimpleSetup ss(dp::makeStateSpace(world->robot()));
  const ompl::base::SpaceInformationPtr& si = ss.getSpaceInformation();
  const dp::StateValidityCheckerPtr checker = std::make_shared<dp::StateValidityChecker>(si, world);
  ss.setStateValidityChecker(checker);
  si->setMotionValidator(std::make_shared<dp::ClearanceMotionValidator>(si, checker));
  ompl::base::ScopedState<> start(si), end(si);
  dp::copyToState(qStart, start.get());
  dp::copyToState(qEnd, end.get());
  ss.setStartAndGoalStates(start, end);
  ss.setup();

  BOOST_TEST(world->isFree(qStart));
  BOOST_TEST(si->isValid(start.get()));
  BOOST_TEST(std::dynamic_pointer_cast<dp::ClearanceMotionValidator>(si->getMotionValidator()) != nullptr);
  bool truth = true;  // a fine discrete check of the motion
  for (int k = 0; k <= 300; ++k) truth = truth && world->isFree(qStart + (k / 300.0) * (qEnd - qStart));
  BOOST_TEST(si->checkMotion(start.get(), end.get()) == truth);
}

BOOST_AUTO_TEST_SUITE_END()
