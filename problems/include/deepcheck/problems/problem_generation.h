#pragma once
// Planning problems generated as MotionBenchMaker (Chamzas et al., RA-L 2022) generates them: a
// nominal MoveIt planning scene varied at random, a start and a goal configuration found by
// inverse kinematics on end-effector poses given relative to objects of the scene, every one
// collision free.
//
// Files read (YAML; every error names the file, the 1-based line and the value):
//   variation file   a list of {names: [..], position: [dx, dy, dz], orientation: [droll,
//                    dpitch, dyaw], type: uniform | gaussian | normal}. For "uniform" each value
//                    is the half-width of a symmetric uniform distribution around 0; for
//                    "gaussian"/"normal" the position values are standard deviations of
//                    zero-mean normal distributions (metres) and the orientation ones uniform
//                    half-widths (radians). The name "World" moves every object together, in
//                    the scene frame (X' = V X); any other name moves that object in its own
//                    frame (X' = X V), one draw per object. V = translation(d) *
//                    Rz(dyaw) Ry(dpitch) Rx(droll).
//   query file       start_queries (optional) and goal_queries: lists of {objects: [..], tag,
//                    offset: {position: [x, y, z], orientation: [x, y, z, w], position_tol:
//                    [tx, ty, tz], orientation_tol: [rx, ry, rz]}, attached}. One query per
//                    object: the end effector at X_O * offset, X_O the object's pose. The
//                    tolerance box (full edge lengths, as MotionBenchMaker's box region, along the
//                    axes of the end-effector target) is the IK's position box (the same edge
//                    lengths, on the query frame: the end effector); the orientation is met
//                    within min(r). Only attached "False" is accepted.
//   robot file       MotionBenchMaker's robot configuration (configs/robots/panda.yaml):
//                    robot_state.joint_state {name: [..], position: [..]}, the default state;
//                    urdf, srdf, kinematics and limits are read as text.
//
// Object pose. A MotionBenchMaker object has one shape and no `pose`; its pose is that shape's
// (MoveIt's older format). Here an object's pose is the pose of its first shape, X_FS[0].
//
// Generation: for each problem, until it succeeds or ProblemOptions::maxAttempts: vary the
// nominal scene (or the one ProblemOptions::drawScene draws), put it in the world, pick a goal
// query (and a start query when the file has any, on another object or tag) uniformly, solve the
// IK of ProblemOptions::tipLink at
//   X_WT = X_WF * X_O * offset * eeOffset^-1
// with solveCollisionFree (valid for the planner: collision free, within bounds); without start
// queries the start is ProblemOptions::start, which must be valid. Everything random comes from
// one std::mt19937_64 seeded with ProblemOptions::seed: the same inputs and seed give the same
// problems.

#include "deepcheck/planners/validity_checker.h"
#include "deepcheck/robots/inverse_kinematics.h"
#include "deepcheck/robots/moveit_scene.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace deepcheck::checker {
class World;
}

namespace deepcheck::problems {

struct SceneVariation {
  std::vector<std::string> names;                         ///< objects, or {"World"}
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     ///< metres (see the file comment)
  Eigen::Vector3d orientation = Eigen::Vector3d::Zero();  ///< roll, pitch, yaw half-widths, rad
  bool normal = false;                                    ///< position drawn from normal distributions (else uniform)
  int line = 0;
};

struct ObjectQuery {
  std::string object;
  std::string tag;
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();        ///< X_OT, the end effector in O
  Eigen::Vector3d positionTolerance = Eigen::Vector3d::Zero();     ///< box edge lengths, metres
  Eigen::Vector3d orientationTolerance = Eigen::Vector3d::Zero();  ///< radians per axis
  int line = 0;
  std::string name() const { return object + "_" + tag; }  ///< "Can3_Front"
};

struct QuerySet {
  std::string source;
  std::vector<ObjectQuery> start;  ///< may be empty
  std::vector<ObjectQuery> goal;   ///< never empty
};

/// MotionBenchMaker's robot configuration file.
struct RobotConfig {
  std::string source;
  std::string urdf, srdf;  ///< as written (package:// URIs)
  std::vector<std::string> jointNames;
  std::vector<double> jointPositions;
  int line = 0;  ///< of robot_state
};

std::vector<SceneVariation> loadSceneVariations(const std::string& path);
std::vector<SceneVariation> parseSceneVariations(const std::string& yaml, const std::string& sourceName);
QuerySet loadQueries(const std::string& path);
QuerySet parseQueries(const std::string& yaml, const std::string& sourceName);
RobotConfig loadRobotConfig(const std::string& path);
RobotConfig parseRobotConfig(const std::string& yaml, const std::string& sourceName);

/// The robot's default configuration with the config's joint positions set. Mimic joints are
/// skipped, and so are locked joints (robot_model.h; a note says so when the file's value is not
/// the locked one); a joint the robot lacks is an error naming it. A value outside the robot's limits (the
/// file may have been written for another model of the robot: MotionBenchMaker's Panda opens its
/// fingers 0.065 m, the moveit_resources Panda 0.04 m) is clamped into them and, when `notes` is
/// given, a line saying so is added to it. A wrapping variable's value (a continuous joint,
/// robots/joint_angles.h) is the same angle normalized to (-pi, pi], without a note.
Eigen::VectorXd configurationOf(const robots::RobotModel& robot, const RobotConfig& config,
                                std::vector<std::string>* notes = nullptr);

/// The variables of `robot` outside the planning group `group` of the SRDF `srdf`, at their
/// values in `config` (clamped into the limits, as configurationOf does): what
/// planners::SetupOptions::lockedVariables holds when a MotionBenchMaker robot is planned by group, the
/// other joints at the robot file's default state, as MoveIt holds them. Throws what
/// readSrdfGroups and groupVariables throw (robots/planning_group.h).
std::map<std::string, double> lockedOutsideGroup(const robots::RobotModel& robot, const RobotConfig& config,
                                                 const std::string& srdf, const std::string& group);

/// The nominal scene with `variations` applied (draws from `rng`). Throws std::invalid_argument
/// naming the variation file's line for an object the scene lacks.
robots::PlanningScene varyScene(const robots::PlanningScene& nominal, const std::vector<SceneVariation>& variations,
                                std::mt19937_64& rng, const std::string& variationSource = "");

/// X_WT of the tip for `query` in `scene` (the object's pose through its frame's link at q).
Eigen::Isometry3d queryPose(const robots::PlanningScene& scene, const ObjectQuery& query,
                            const robots::RobotModel& robot, const Eigen::Ref<const Eigen::VectorXd>& q,
                            const robots::FrameAliases& aliases, const Eigen::Isometry3d& eeOffset);

/// IK tolerances meeting a query's tolerance box (see the file comment): `base` with the box's
/// edge lengths as the position box, applied to the query frame (X_LB = eeOffset, the query frame
/// in the tip's frame), and the smallest orientation tolerance.
robots::IkOptions queryIkOptions(const ObjectQuery& query, const robots::IkOptions& base,
                                 const Eigen::Isometry3d& eeOffset);

/// Draws an attempt's scene before the variation file, from the generation's generator.
using SceneDraw = std::function<robots::PlanningScene(std::mt19937_64& rng)>;

struct ProblemOptions {
  std::string tipLink;                                         ///< the end effector's link (required)
  Eigen::Isometry3d eeOffset = Eigen::Isometry3d::Identity();  ///< query frame in the tip frame
  robots::FrameAliases frameAliases;
  Eigen::VectorXd start;  ///< start when the queries have none (required then)
  std::uint64_t seed = 0;
  int maxAttempts = 100;  ///< per problem
  robots::IkOptions ik;   ///< iterations and restarts (tolerances come from the query)
  /// When set, each attempt varies the scene this draws instead of the nominal one: a scene given
  /// as a URDF with its joints (doors, sliding bars) drawn within their limits, as MotionBenchMaker
  /// does. Its objects carry the nominal scene's names (the queries are checked against those).
  SceneDraw drawScene;
};

struct Problem {
  robots::PlanningScene scene;  ///< the varied scene
  Eigen::VectorXd start, goal;
  std::string startQuery;                                      ///< "" when the start is ProblemOptions::start
  std::string goalQuery;                                       ///< "Can3_Front"
  Eigen::Isometry3d goalPose = Eigen::Isometry3d::Identity();  ///< X_WT of the tip
  robots::PoseError goalError;  ///< of `goal` against goalPose, with the query's tolerances
  int attempts = 0;             ///< scenes drawn for this problem
};

/// Called after each problem (index from 0).
using ProblemProgress = std::function<void(int index, const Problem& problem)>;

/// Generates `count` problems. `world` holds the robot only (its obstacles are replaced during
/// generation and left empty); `checker` is a validity checker on it. Throws std::runtime_error
/// when a problem cannot be generated within maxAttempts (naming the queries tried) and
/// std::invalid_argument for bad input.
std::vector<Problem> generateProblems(checker::World& world, const planners::StateValidityChecker& checker,
                                      const robots::PlanningScene& nominal,
                                      const std::vector<SceneVariation>& variations, const QuerySet& queries,
                                      const ProblemOptions& options, int count, const ProblemProgress& progress = {},
                                      const std::string& variationSource = "");

}  // namespace deepcheck::problems
