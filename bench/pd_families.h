#pragma once
// Test families of the penetration-depth benchmark: generated pairs of convex hulls and poses.
//
// A family is a set of shapes (ConvexPolytope, built once) and a list of queries, each a pair of
// shape indices with their poses X_WA, X_WB. Every method of the benchmark answers the same
// queries. Random families are generated from a pinned std::mt19937 seeded from the family's
// name, so a family is the same whether it runs alone or with the others.
//
// Warm starts. A warm-started method is handed, before each query, the cache state a previous
// query of the same pair left behind:
//   - sequence families (motion): the previous step of the trajectory (the natural sequence);
//   - all other families: a query of the same pair at a nearby pose (B moved by 1 % of the pair's
//     size L in a random direction and turned by 0.01 rad about a random axis), as a planner
//     that checks neighbouring states would have made just before. That priming query is not
//     timed and not scored; only the query at the family's pose is.

#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/polytope.h"

#include <Eigen/Geometry>

#include <optional>
#include <random>
#include <string>
#include <vector>

namespace deepcheck::bench {

/// A rigid pose stored as a unit quaternion and a translation, so that the exact input can be
/// written to a reproducer file.
struct Pose {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Isometry3d iso() const;
};

struct Query {
  int a = 0;  ///< shape index of A
  int b = 0;  ///< shape index of B
  Pose poseA, poseB;
  Eigen::Isometry3d X_WA, X_WB;                ///< poseA.iso(), poseB.iso()
  std::optional<Pose> primeB;                  ///< non-sequence families: B's pose of the priming query
  std::optional<geometry::ExactResult> exact;  ///< exact answer, computed once per run
  double exactMicros = 0.0;                    ///< time of that exact computation
};

struct Family {
  std::string name;
  std::string description;
  int nominalVertices = 0;  ///< vertices per hull for the scaling families, else 0
  bool sequence = false;    ///< queries are consecutive steps of one pair each (trajectories)
  std::vector<geometry::ConvexPolytope> shapes;
  std::vector<std::vector<Eigen::Vector3d>> points;  ///< the points each shape is the hull of
  std::vector<Query> queries;

  /// Adds the hull of `pts` (own frame) as a shape; returns its index.
  int addShape(std::vector<Eigen::Vector3d> pts, const std::string& shapeName = "points");

  /// Pair length scale used by the error measure: the larger bounding radius of the two hulls.
  double pairScale(const Query& q) const;
};

/// The family names in the order they run.
std::vector<std::string> familyNames();

/// Builds family `name` with about `pairs` queries (the motion family: `pairs` steps in all,
/// in trajectories of 500 steps, at least one).
/// `sharedDir` is the folder holding robots/ (for the robot family); returns std::nullopt with
/// a message on stderr when the family cannot be built (robot meshes absent).
std::optional<Family> makeFamily(const std::string& name, int pairs, const std::string& sharedDir);

/// The exact answer of query q (computed on first use, with its time, then cached in q).
const geometry::ExactResult& exactOf(const Family& family, Query& q);

/// Reads the vertices of an STL file (binary or ASCII). Throws std::runtime_error.
std::vector<Eigen::Vector3d> readStlVertices(const std::string& path);

}  // namespace deepcheck::bench
