#pragma once
// Collision-pair filtering: which pairs of links of one robot never need a self-collision check,
// found the way MoveIt's setup assistant finds them (moveit_setup_assistant,
// compute_default_collisions.cpp); the pairs are read from and written to SRDF files by srdf.h.
//
// Only links WITH collision geometry take part: a pair is a set of two distinct links that both
// have at least one collision piece (collision_geometry.h). Every such pair gets at most one
// reason, tested in this order (the first that applies wins):
//   Adjacent  the two links are joined by a joint, or joined through links without collision
//             geometry only (those are transparent: the Panda's panda_link8, a flange between
//             panda_link7 and panda_hand, makes link7 and hand adjacent). Adjacent links touch
//             at their joint by design.
//   Default   the pieces of the two links overlap at the default configuration
//             (PairFilterOptions::defaultConfiguration if given, else MoveIt's default state: each
//             variable 0 when 0 is within its limits, else the middle of its limits; see
//             pairFilterDefaultConfiguration()). MoveIt disables these as 'Default'. A pair
//             that overlaps at the default configuration but not elsewhere is then never
//             checked: on the Panda (moveit_resources URDF, joint 6 at 0 folds the hand onto
//             link 5) link5-link7 and link5-hand come out 'Default' although MoveIt's shipped
//             SRDF keeps them. Set checkDefault = false, or choose defaultConfiguration, when
//             the default pose is not a resting pose; LinkPairReport::collisions shows how
//             often a Default pair collides in the random samples.
//   Always    they overlap in at least `alwaysFraction` of the random samples (MoveIt: 95 %).
//   Never     they overlap in none of the random samples.
// The remaining pairs (sometimes in collision) are the ones a planner must check.
//
// Collision test at a configuration q: forward kinematics (kinematics.h) gives X_WL of every
// link; piece P of link L is posed at X_WL * X_LP; two links collide when any piece of one
// overlaps any piece of the other (geometry::overlaps: GJK, touching counts as overlap), after a
// bounding-sphere test. Random samples are uniform in the joint limits of every variable
// (continuous joints in [-pi, pi], robot_model.h), drawn from a std::mt19937_64 seeded with
// `seed`; the uniform numbers are made from its raw output (not std::uniform_real_distribution,
// whose algorithm the standard leaves to each library), so a seed gives the same pairs on every
// platform.
//
// Conservative by construction. The pieces CONTAIN the meshes (collision_geometry.h: hulls,
// circumscribed prisms, covering decompositions), so a pair whose pieces never overlap in the
// sample has meshes that never touch there either. With the default hull-per-mesh decomposer the
// pieces are noticeably larger than non-convex meshes, so fewer pairs come out 'Never' than with
// a fine decomposition, and some may come out 'Default' or 'Always' that would not with exact
// meshes. 'Never' is a statistical statement: a pair that collides in a small region of the
// configuration space (fraction p) is missed with probability (1 - p)^samples.
//
// SRDF files (the disabled pairs read and written): srdf.h.
//
// Errors: bad input throws std::invalid_argument whose message names the file (or the robot), the
// link and the offending value.

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::robots {

/// MoveIt's default number of random configurations for 'Always' and 'Never' (its "sampling
/// density" slider starts at 10,000).
constexpr int kDefaultPairFilterSamples = 10000;
/// MoveIt's min_collision_fraction: a pair colliding in at least this fraction of the samples is
/// 'Always' in collision (dimensionless).
constexpr double kDefaultAlwaysFraction = 0.95;

struct PairFilterOptions {
  /// Random configurations drawn for 'Always' and 'Never' (>= 0; 0 skips both).
  int samples = kDefaultPairFilterSamples;
  /// Seed of the std::mt19937_64 that draws them.
  std::uint64_t seed = 1;
  /// A pair colliding in at least this fraction of the samples is 'Always', in (0, 1].
  double alwaysFraction = kDefaultAlwaysFraction;
  /// Disable the pairs colliding at the default configuration ('Default').
  bool checkDefault = true;
  /// The default configuration; empty (size 0) means pairFilterDefaultConfiguration(model).
  Eigen::VectorXd defaultConfiguration;
};

/// MoveIt's default state (JointModel::getVariableDefaultPositions): each variable 0 when 0 is
/// within its limits, else the middle of its limits. Unlike RobotModel::defaultConfiguration()
/// (zero clamped into the limits) it keeps a joint whose range excludes 0 away from its limit: a
/// joint limited to [-3.07, -0.07] is -1.57 here, not -0.07.
Eigen::VectorXd pairFilterDefaultConfiguration(const RobotModel& model);

/// A pair of links with geometry and what the filter found about it.
struct LinkPairReport {
  int link1 = -1;  ///< link indices, link1 < link2
  int link2 = -1;
  /// Random samples in which the two links collided (Default pairs included, so that a Default
  /// pair that rarely collides, a sign of pieces larger than the meshes, can be spotted; 0 for
  /// Adjacent pairs, which are not sampled).
  int collisions = 0;
  /// Why the pair is disabled; empty when it must be checked.
  std::optional<DisableReason> reason;
};

struct PairFilterResult {
  int numGeometryLinks = 0;  ///< links with at least one collision piece
  int samples = 0;           ///< random configurations drawn
  /// Every pair of links with geometry, by (link1, link2) in link order.
  std::vector<LinkPairReport> pairs;
  /// The disabled pairs (link1 = the link earlier in link order), in the order of `pairs`.
  std::vector<DisabledPair> disabled;

  int numPairs() const { return static_cast<int>(pairs.size()); }
  /// Number of disabled pairs with that reason.
  int count(DisableReason reason) const;
  /// Pairs left to check (numPairs() minus the disabled ones).
  int numEnabled() const;
};

/// Pairs of links with geometry that are adjacent (see the header comment), as (i, j) link
/// indices with i < j, sorted. `pieces` is collisionPieces(model) (result[link]).
std::vector<std::pair<int, int>> adjacentLinkPairs(const RobotModel& model,
                                                   const std::vector<std::vector<CollisionPiece>>& pieces);

/// Tests every pair of links with geometry at the link poses X_WL (forwardKinematics()) and
/// returns the colliding ones as (i, j) link indices, i < j, sorted. Adjacent pairs are included
/// (they usually collide). For tests and tools.
std::vector<std::pair<int, int>> collidingLinkPairs(const RobotModel& model,
                                                    const std::vector<std::vector<CollisionPiece>>& pieces,
                                                    const std::vector<Eigen::Isometry3d>& X_WL);

/// True when some piece of `a` (posed at X_WA * X_LP) overlaps some piece of `b`.
bool piecesOverlap(const std::vector<CollisionPiece>& a, const Eigen::Isometry3d& X_WA,
                   const std::vector<CollisionPiece>& b, const Eigen::Isometry3d& X_WB);

/// Runs the filter (see the header comment). `pieces` must be collisionPieces(model) or any
/// per-link pieces with one entry per link. Throws std::invalid_argument naming the robot and the
/// value for a bad option (negative samples, alwaysFraction outside (0, 1], a given default
/// configuration of the wrong size or not finite) or pieces of the wrong size.
PairFilterResult computeDisabledPairs(const RobotModel& model, const std::vector<std::vector<CollisionPiece>>& pieces,
                                      const PairFilterOptions& options = {});

/// Link pairs (i, j), i < j, both with geometry, that are NOT disabled by `disabled`: the pairs
/// a self-collision check must test. Throws std::invalid_argument when a disabled pair names a
/// link the model does not have.
std::vector<std::pair<int, int>> enabledLinkPairs(const RobotModel& model,
                                                  const std::vector<std::vector<CollisionPiece>>& pieces,
                                                  const std::vector<DisabledPair>& disabled);

/// Throws std::invalid_argument, naming `source` (e.g. the SRDF file), the pair and the link, when
/// a pair names a link `model` does not have or the same link twice.
void checkDisabledPairs(const RobotModel& model, const std::vector<DisabledPair>& disabled, const std::string& source);

}  // namespace deepcheck::robots
