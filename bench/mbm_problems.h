#pragma once
// The MotionBenchMaker scenes of mbm_bench (bench/README.md, "MotionBenchMaker benchmark") and
// their generated problems.
//
// Each scene is MotionBenchMaker's Panda dataset specification: its configs/problems/<name>_panda.yaml
// (not in ../shared; its values are copied into mbmScenes()) names the scene, variation and query
// files, read from ../shared, and gives base_offset (where the scene goes relative to the robot)
// and ee_offset (the query frame relative to the arm's tip). Scenes given as
// a URDF (kitchen, table_bars) become a planning scene here: one object per link with collision
// geometry, named as the link (the names the variation and query files use), posed for each
// attempt at joint values drawn uniformly within their limits (the kitchen's doors, the sliding
// bars), as MotionBenchMaker does; then the variation file moves the links. Problems come from
// deepcheck::problems::generateProblems (the scene varied, the goal and, when the query file has start queries, the
// start by collision-free inverse kinematics of panda_hand; otherwise MotionBenchMaker's Panda default state).

#include "options.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/validity_checker.h"
#include "deepcheck/problems/problem_generation.h"
#include "deepcheck/robots/moveit_scene.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace deepcheck::bench {

struct MbmScene {
  std::string name;       ///< "bookshelf_small"
  std::string scene;      ///< planning-scene YAML or scene URDF
  std::string variation;  ///< variation file
  std::string queries;    ///< query file
  /// MotionBenchMaker's base_offset: every object is moved by it in the world (X' = base * X).
  Eigen::Isometry3d baseOffset = Eigen::Isometry3d::Identity();
  /// MotionBenchMaker's ee_offset: the query frame in the tip's frame (ProblemOptions::eeOffset).
  Eigen::Isometry3d eeOffset = Eigen::Isometry3d::Identity();
};

/// Every scene, in the order of the tables.
std::vector<MbmScene> mbmScenes();

/// The scenes named (all when none), in the order named; an unknown name is a usage error.
std::vector<MbmScene> selectScenes(const std::vector<std::string>& wanted, Usage usage);

/// The frame aliases of the MotionBenchMaker files for the Panda of ../shared (base_link is
/// panda_link0).
robots::FrameAliases pandaFrameAliases();

/// The Panda as MotionBenchMaker plans it: its SRDF's panda_arm group (the seven arm joints),
/// the fingers held at MotionBenchMaker's default state (clamped into this Panda's limits).
planners::SetupOptions pandaArmOptions();

/// The nominal planning scene: the YAML as read, or the URDF's links as objects at the URDF's
/// default joint values (header comment); for a URDF, `draw` (when not null) is set to draw its
/// joints, from the same model. Throws std::invalid_argument (naming the file) when it cannot be
/// read.
robots::PlanningScene loadNominalScene(const MbmScene& scene, problems::SceneDraw* draw = nullptr);

/// Problem generation options for the Panda in `scene`: the tip panda_link8 (the end of
/// MotionBenchMaker's panda_arm group) with the scene's ee_offset, the start from MotionBenchMaker's
/// Panda file (`notes` says what was clamped into the limits).
problems::ProblemOptions pandaProblemOptions(const MbmScene& scene, const robots::RobotModel& panda, std::uint64_t seed,
                                             std::vector<std::string>* notes);

/// `count` problems of `scene` in `world` (the Panda alone; its obstacles are left empty), through
/// generateProblems; `progress` after each. Throws what loading and generation throw.
std::vector<problems::Problem> generateMbmProblems(const MbmScene& scene, checker::World& world,
                                                   const planners::StateValidityChecker& checker,
                                                   const problems::ProblemOptions& options, int count,
                                                   const problems::ProblemProgress& progress);

/// Replaces the obstacles of `world` by the objects of `scene` (frame aliases of the Panda).
void placeScene(checker::World& world, const robots::PlanningScene& scene);

}  // namespace deepcheck::bench
