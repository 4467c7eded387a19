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
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace deepcheck::checker::detail {

/// A robot piece in its link's frame, with its bounding sphere (centre in the link frame).
struct RobotPiece {
  std::shared_ptr<const geometry::ConvexPolytope> core;
  double radius = 0.0;
  Eigen::Isometry3d X_LP = Eigen::Isometry3d::Identity();
  Eigen::Vector3d center_L = Eigen::Vector3d::Zero();
  double sphereRadius = 0.0;
  Obb obb_L;  // oriented box in the link frame
  int link = -1;
  int group = -1;  // its LinkGeometry (index into RobotData::links)
};

/// A robot link that has pieces, or an object attached to a link: pieces
/// [firstPiece, firstPiece + numPieces) and their bounding sphere in the link frame.
struct LinkGeometry {
  int link = -1;
  int attached = -1;  // index into Snapshot::attached for an attached object, -1 for the link's own
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

/// Everything about the robot: its own links built once (WorldState::robot), and in a snapshot
/// with attached objects a copy with one more LinkGeometry per object, after the links' own
/// (world_attached.cpp).
struct RobotData {
  robots::RobotModel model;
  std::vector<RobotPiece> pieces;                  // grouped by link, in link order
  std::vector<LinkGeometry> links;                 // links with pieces, in link order
  std::vector<std::vector<int>> chains;            // per link geometry: its moving joints, up to the root
  std::vector<ReachSphere> reach;                  // per link
  std::shared_ptr<const LinkPairIndex> linkPairs;  // adjacent and rigid link pairs
};

/// A world piece (scene or obstacle), posed in the world.
struct WorldPiece {
  std::shared_ptr<const geometry::ConvexPolytope> core;
  double radius = 0.0;
  Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();
  Eigen::Vector3d center_W = Eigen::Vector3d::Zero();
  double sphereRadius = 0.0;
  Aabb box;
  Obb obb_W;              // oriented box in the world
  int body = -1;          // index into PieceSet::bodies
  std::uint64_t uid = 0;  // stable across snapshots (obstacle id << 24 | piece), for caches
};

struct WorldBody {
  BodyRef ref;
  std::string name;
};

/// World pieces with their broad-phase structures; immutable once built.
struct PieceSet {
  std::vector<WorldPiece> pieces;
  std::vector<WorldBody> bodies;
  AabbTree tree;
  std::shared_ptr<const PieceTree> external;  // WorldOptions::externalBroadPhase's, when set
};

/// A scene piece the reach filter dropped, kept aside: an attached object may reach it later
/// (reclaimScenePieces).
struct DroppedPiece {
  int link = -1;  // scene link
  WorldPiece piece;
};

/// One scene as loaded.
struct SceneData {
  robots::RobotModel model;
  Eigen::VectorXd q;
  std::vector<Eigen::Isometry3d> X_WL;
  int piecesKept = 0;
  int piecesDropped = 0;
  int linksWithGeometry = 0;
  std::vector<DroppedPiece> dropped;
};

/// One obstacle as given, with its pieces in its own frame O.
struct ObstacleData {
  int id = -1;
  Obstacle source;
  std::vector<robots::CollisionPiece> pieces;  // X_LP = pose of the piece in O
  double excess = 0.0;
};

/// An object attached to a robot link (world_attached.cpp): its pieces in its frame O, O's pose
/// in the link frame, and the links it may touch (its own link always may).
struct AttachedData {
  Obstacle source;  // X_WO as given when attached (not updated)
  int link = -1;
  Eigen::Isometry3d X_LO = Eigen::Isometry3d::Identity();
  std::vector<robots::CollisionPiece> pieces;  // X_LP = pose of the piece in O
  std::vector<int> touchLinks;
};

/// Allowed collisions by name (world_allowed.cpp): pairs of names (first < second), and names
/// allowed to touch anything. A name stands for every body it is an alias of (bodyAliases).
struct AllowedNames {
  std::set<std::pair<std::string, std::string>> pairs;
  std::set<std::string> always;
  bool empty() const { return pairs.empty() && always.empty(); }
};

/// Which (robot geometry, world body) pairs of one PieceSet are allowed: bits[g * bodies + body];
/// empty when none is.
struct AllowedMask {
  std::size_t bodies = 0;
  std::vector<std::uint8_t> bits;
  bool test(int g, int body) const {
    return !bits.empty() && bits[static_cast<std::size_t>(g) * bodies + static_cast<std::size_t>(body)] != 0;
  }
};

/// Shortcuts of the queries that never change an answer, both on unless turned off to find the
/// same answers the long way (a World's internal setting, not an option).
struct Shortcuts {
  /// Certified-free grids for the self pairs whose relative pose depends on one or two variables
  /// (self_pair_grid.h): isFree skips such a pair when q lies in a cell where it was proved apart.
  bool selfPairGrids = true;
  /// isFree: before GJK on a robot piece against a world piece of at most 32 faces, test whether
  /// the robot piece's centroid (a point of its core) lies inside the world piece, deeper than
  /// twice its hull tolerance: then they overlap, as GJK would find.
  bool centroidTest = true;
};

/// Sent to WorldState::onNarrowPhase before every narrow-phase call.
struct NarrowPhaseEvent {
  int linkA = -1;
  BodyRef bodyB;
};

struct Snapshot {
  Shortcuts shortcuts;  // carried from snapshot to snapshot
  std::shared_ptr<const RobotData> robot;
  std::vector<std::shared_ptr<const AttachedData>> attached;  // robot->links beyond the own ones
  AllowedNames allowed;
  AllowedMask sceneAllowed;  // from `allowed`, rebuilt by publish()
  AllowedMask obstacleAllowed;
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
  double excess = 0.0;
};

/// The shared state of a World (the World object itself only holds a pointer to it, so moving a
/// World keeps its contexts valid).
struct WorldState {
  World::Options options;
  std::uint64_t uid = 0;     // unique per World ever made in this process
  mutable std::mutex mutex;  // guards `current` and the fields below during changes
  std::shared_ptr<const Snapshot> current;
  std::atomic<std::uint64_t> generation{0};
  int nextObstacleId = 0;
  /// Largest concavity of the meshes decomposed so far (written by the decomposer, under
  /// `mutex` or in the constructor); NaN when unknown.
  std::shared_ptr<double> excessSink;
  robots::CollisionGeometryOptions geometry;  // with the decomposer resolved
  /// Fixed pairs already reported ("<nameA>\n<nameB>"), so each is reported once (under `mutex`).
  std::set<std::string> reportedFixedPairs;
  /// World::setFixedPairReports: while false, nothing is reported.
  std::atomic<bool> fixedPairReports{true};
  /// The robot, the same in every snapshot: read without the mutex (World::robot() is called on
  /// every validity query).
  std::shared_ptr<const RobotData> robot;
  /// When set, called before every narrow-phase call of every query (an observer of which pairs
  /// get there; set it while no query runs).
  std::function<void(const NarrowPhaseEvent&)> onNarrowPhase;
  /// isFreeBatch runs its baseline lane loops even where AVX2 is available (set by tests, to
  /// compare the two; the answers are the same).
  std::atomic<bool> batchBaseline{false};

  std::shared_ptr<const Snapshot> snapshot() const {
    std::lock_guard<std::mutex> lock(mutex);
    return current;
  }
};

/// Pieces of one URDF-like geometry (box, sphere, cylinder prism, decomposed mesh) in its frame G.
std::vector<robots::CollisionPiece> piecesOfGeometry(const robots::Geometry& geometry, const robots::TriangleMesh* mesh,
                                                     const robots::CollisionGeometryOptions& options,
                                                     const std::string& what);

/// Appends to `robot` the geometry of `link` (attached: -1 for the link's own pieces, else the
/// index of its attached object) made of `pieces` posed at X_LB in the link frame.
void appendLinkGeometry(RobotData& robot, int link, int attached, const std::vector<robots::CollisionPiece>& pieces,
                        const Eigen::Isometry3d& X_LB);

/// A world piece from a collision piece of a body posed at X_WB: its bounding box, sphere and
/// oriented box.
WorldPiece makeWorldPiece(const robots::CollisionPiece& p, const Eigen::Isometry3d& X_WB, int body, std::uint64_t uid);

/// Builds the broad phase of `set`: its AABB tree, and the external one when `external` is given
/// (WorldOptions::externalBroadPhase).
void finishPieceSet(PieceSet& set, const PieceTreeFactory* external);

/// Appends obstacle o's body and world pieces to `set` (finishPieceSet rebuilds its tree).
void appendObstacle(PieceSet& set, const ObstacleData& o);
/// The pieces of the obstacles, in their order (world_obstacles.cpp).
std::shared_ptr<const PieceSet> buildObstaclePieces(const std::vector<std::shared_ptr<const ObstacleData>>& obstacles,
                                                    const PieceTreeFactory* external);

/// Reports on options.progress the fixed pairs (World::fixedPairs) not reported before, one line
/// each naming the pair, its distance and how to allow it (world_fixed_pairs.cpp). Call without
/// holding the mutex.
void reportFixedPairs(const World& world, WorldState& st);
/// That line, and its advice alone ("allow it with --allow-collision A:B ...").
std::string fixedPairMessage(const Contact& c, const robots::RobotModel& robot);
std::string allowHint(const Contact& c);

/// Publishes a new snapshot (caller holds the mutex): its allowed masks are rebuilt first.
void publish(WorldState& st, std::shared_ptr<Snapshot> snap);

/// The names a body answers to in allowed collisions (world_allowed.cpp): a robot link its name;
/// a scene link "scene/<link>" and <link>; an obstacle "obstacle/<name>" and <name>, and for a
/// name "<id>/<k>" (a planning-scene object's k-th shape) also <id> and "obstacle/<id>"; an
/// attached object likewise with "attached/". A name without its prefix that is also a robot
/// link's name is left out: it names the link only.
std::vector<std::string> bodyAliases(const std::string& bodyName, const robots::RobotModel& robot);
/// The aliases of robot geometry g of `s` (a link's name, or its attached object's aliases).
std::vector<std::string> groupAliases(const Snapshot& s, int g);
/// True when the bodies with aliases a and b may touch.
bool allowedByName(const AllowedNames& allowed, const std::vector<std::string>& a, const std::vector<std::string>& b);
/// Rebuilds s.sceneAllowed and s.obstacleAllowed from s.allowed.
void buildAllowedMasks(Snapshot& s);
/// Self pairs (robot links with geometry, first < second) that s.allowed allows.
std::set<std::pair<int, int>> allowedLinkPairs(const Snapshot& s);
/// Rebuilds s.selfPairs (world.cpp): after a change of the allowed names or attached objects.
void rebuildSelfPairs(Snapshot& s, const WorldOptions& options);
/// s.robot made again from the robot's own data and s.attached, its reach spheres grown by the
/// attached objects (world_attached.cpp).
void attachToRobot(Snapshot& s, const std::shared_ptr<const RobotData>& own);
/// True when the box is within `margin` of a reach sphere (world.cpp).
bool reachable(const std::vector<ReachSphere>& reach, const Aabb& box, double margin);
/// Moves the dropped scene pieces that s.robot's reach spheres now reach into s.scenePieces
/// (world.cpp): after an attachment grew them.
void reclaimScenePieces(Snapshot& s, double reachMargin, const PieceTreeFactory* external);

/// Pads a bounding radius for round-off (tol::kBoundingRelative).
inline double padRadius(double r, const Eigen::Vector3d& center) {
  return r + tol::kBoundingRelative * (r + center.norm());
}

}  // namespace deepcheck::checker::detail
