#pragma once
// Private data of World and World::Context (world.cpp builds it; the queries read it,
// world_queries_internal.h).
//
// A World owns an immutable Snapshot behind a shared_ptr; every change makes a new one. Contexts
// hold the snapshot they were last refreshed with, so a query never sees a half-made change.

#include "aabb_tree.h"
#include "obb.h"
#include "link_pairs.h"
#include "reach.h"
#include "deepcheck/checker/world.h"

#include "self_pair_grid.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace deepcheck::checker::detail {

/// A robot piece in its link's frame, with its bounding sphere (centre in the link frame).
struct RobotPiece {
  std::shared_ptr<const deep::ConvexPolytope> core;
  double radius = 0.0;
  Eigen::Isometry3d X_LP = Eigen::Isometry3d::Identity();
  Eigen::Vector3d center_L = Eigen::Vector3d::Zero();
  double sphereRadius = 0.0;
  Obb obb_L;  // oriented box in the link frame
  int link = -1;
};

/// A robot link that has pieces: pieces [firstPiece, firstPiece + numPieces) and their bounding
/// sphere in the link frame.
struct LinkGeometry {
  int link = -1;
  int firstPiece = 0;
  int numPieces = 0;
  Eigen::Vector3d center_L = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// An allowed self pair: link geometries a < b (indices into RobotData::links), the offset of
/// its numPieces(a) x numPieces(b) block of warm-start caches, and its certified-free grid when
/// its relative pose depends on one or two variables (self_pair_grid.h; null otherwise).
struct SelfPair {
  int a = 0;
  int b = 0;
  int cacheOffset = 0;
  std::shared_ptr<const SelfPairGrid> grid;
};

/// Everything about the robot: built once, shared by all snapshots.
struct RobotData {
  robots::RobotModel model;
  std::vector<RobotPiece> pieces;   // grouped by link, in link order
  std::vector<LinkGeometry> links;  // links with pieces, in link order
  std::vector<ReachSphere> reach;   // per link
  std::shared_ptr<const LinkPairIndex> linkPairs;  // adjacent and rigid link pairs
};

/// A world piece (scene or obstacle), posed in the world.
struct WorldPiece {
  std::shared_ptr<const deep::ConvexPolytope> core;
  double radius = 0.0;
  Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();
  Eigen::Vector3d center_W = Eigen::Vector3d::Zero();
  double sphereRadius = 0.0;
  Aabb box;
  Obb obb_W;                // oriented box in the world
  int body = -1;            // index into PieceSet::bodies
  std::uint64_t uid = 0;    // stable across snapshots (obstacle id << 24 | piece), for caches
};

struct WorldBody {
  BodyRef ref;
  std::string name;
};

class ExternalPieceTree;  // external_broad_phase.h

/// World pieces with their broad-phase structures; immutable once built.
struct PieceSet {
  std::vector<WorldPiece> pieces;
  std::vector<WorldBody> bodies;
  AabbTree tree;
  std::shared_ptr<const ExternalPieceTree> fclTree;  // only with BroadPhase::FclTree
};

/// One scene as loaded.
struct SceneData {
  robots::RobotModel model;
  Eigen::VectorXd q;
  std::vector<Eigen::Isometry3d> X_WL;
  int piecesKept = 0;
  int piecesDropped = 0;
  int linksWithGeometry = 0;
};

/// One obstacle as given, with its pieces in its own frame O.
struct ObstacleData {
  int id = -1;
  Obstacle source;
  std::vector<robots::CollisionPiece> pieces;  // X_LP = pose of the piece in O
  double excess = 0.0;
};

struct Snapshot {
  std::shared_ptr<const RobotData> robot;
  std::vector<std::shared_ptr<const SceneData>> scenes;
  std::vector<std::shared_ptr<const ObstacleData>> obstacles;  // by increasing id
  std::shared_ptr<const PieceSet> scenePieces;
  std::shared_ptr<const PieceSet> obstaclePieces;
  std::vector<SelfPair> selfPairs;
  int selfCacheSize = 0;
  int disabledAdjacent = 0;
  int disabledRigid = 0;
  int disabledByUser = 0;
  int unreachablePairs = 0;  // link pairs neither disabled nor checked: never within the reach margin
  std::vector<std::pair<int, int>> userDisabled;  // link pairs, first < second
  double excess = 0.0;
};

/// The shared state of a World (the World object itself only holds a pointer to it, so moving a
/// World keeps its contexts valid).
struct WorldState {
  World::Options options;
  std::uint64_t uid = 0;  // unique per World ever made in this process
  mutable std::mutex mutex;  // guards `current` and the fields below during changes
  std::shared_ptr<const Snapshot> current;
  std::atomic<std::uint64_t> generation{0};
  int nextObstacleId = 0;
  /// Largest concavity of the meshes decomposed so far (written by the decomposer, under
  /// `mutex` or in the constructor); NaN when unknown.
  std::shared_ptr<double> excessSink;
  robots::CollisionGeometryOptions geometry;  // with the decomposer resolved
  /// The robot, the same in every snapshot: read without the mutex (World::robot() is called on
  /// every validity query).
  std::shared_ptr<const RobotData> robot;

  std::shared_ptr<const Snapshot> snapshot() const {
    std::lock_guard<std::mutex> lock(mutex);
    return current;
  }
};

/// Pieces of one URDF-like geometry (box, sphere, cylinder prism, decomposed mesh) in its frame G.
std::vector<robots::CollisionPiece> piecesOfGeometry(const robots::Geometry& geometry,
                                                     const robots::TriangleMesh* mesh,
                                                     const robots::CollisionGeometryOptions& options,
                                                     const std::string& what);

/// A world piece from a collision piece of a body posed at X_WB: its bounding box, sphere and
/// oriented box.
WorldPiece makeWorldPiece(const robots::CollisionPiece& p, const Eigen::Isometry3d& X_WB, int body, std::uint64_t uid);

/// Builds the broad phase of `set` (its AABB tree, and FCL's tree when asked).
void finishPieceSet(PieceSet& set, BroadPhase broadPhase);

/// Appends obstacle o's body and world pieces to `set` (finishPieceSet rebuilds its tree).
void appendObstacle(PieceSet& set, const ObstacleData& o);
/// The pieces of the obstacles, in their order (world_obstacles.cpp).
std::shared_ptr<const PieceSet> buildObstaclePieces(const std::vector<std::shared_ptr<const ObstacleData>>& obstacles,
                                                    BroadPhase broadPhase);

/// Publishes a new snapshot (caller holds the mutex).
void publish(WorldState& st, std::shared_ptr<Snapshot> snap);

/// Pads a bounding radius for round-off (tol::kBoundingRelative).
inline double padRadius(double r, const Eigen::Vector3d& center) {
  return r + tol::kBoundingRelative * (r + center.norm());
}

}  // namespace deepcheck::checker::detail
