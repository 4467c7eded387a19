#pragma once
// An OMPL state validity checker on the FCL reference backend (fcl_backend.h): the
// robot's and scenes' ORIGINAL meshes (fcl::BVHModel), not the convex pieces. The baseline of the
// planning benchmark and the ground truth of the planning tests.
//
// isValid: within the bounds and FCL finds no colliding allowed pair. clearance: FCL's minimum
// distance over allowed pairs when free, 0 when colliding (FCL's mesh distance gives no
// penetration depth), hence clearanceComputationType = APPROXIMATE.
//
// Thread safety: FclWorld poses its robot objects in place, so every query takes a mutex; const
// calls from several threads are safe but serialized.

#include "deepcheck/fcl_reference/fcl_backend.h"
#include "deepcheck/checker/world.h"
#include "deepcheck/planners/state_space.h"

#include <Eigen/Core>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include <memory>
#include <mutex>

namespace deepcheck::fcl_reference {

class FclStateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  /// Builds the FCL world from `world` (its robot, scenes and obstacles as they are now). States
  /// map to configurations by makeStateMapping (state_space.h). Throws std::invalid_argument for
  /// a state space whose layout is not understood or a mesh FCL cannot load.
  FclStateValidityChecker(ompl::base::SpaceInformation* si, const checker::World& world);
  FclStateValidityChecker(const ompl::base::SpaceInformationPtr& si, const checker::World& world);
  ~FclStateValidityChecker() override;

  bool isValid(const ompl::base::State* state) const override;
  double clearance(const ompl::base::State* state) const override;

  /// FCL's boolean test (no bounds check).
  bool isFree(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// FCL's distance when free, 0 when colliding.
  double distance(const Eigen::Ref<const Eigen::VectorXd>& q) const;

 private:
  planners::StateMapping mapping_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
  mutable std::mutex mutex_;
  std::unique_ptr<FclWorld> fcl_;
};

}  // namespace deepcheck::fcl_reference
