#pragma once
// The collision world: one robot, scenes and obstacles, as posed convex pieces; the queries a
// planner makes for a configuration q of the robot.
//
// What is modeled.
//   Robot     a robots::RobotModel; each link with collision geometry is a set of convex pieces
//             (robots/collision_geometry.h; meshes are convex-decomposed, with an on-disk cache).
//             Links without geometry take no part in any query.
//   Scenes    RobotModels too (a URDF kitchen, a shelf), placed at their base pose with their
//             joints fixed (at given values or their default configuration). Their pieces are
//             posed once, at load, in world coordinates. A scene piece that no robot link can
//             ever reach (farther than WorldOptions::reachMargin from every link's reach sphere,
//             checker/src/reach.h) is DROPPED at load and counted in summary().
//   Obstacles boxes, spheres, cylinders and meshes added, moved and removed at run time by id.
//             They are not subject to the reach filter.
//
// Pairs. Robot-world pairs: every robot link with geometry against every scene and obstacle
// piece. Self pairs: every pair of robot links with geometry that can ever come within
// WorldOptions::reachMargin of each other (their reach spheres, checker/src/reach.h; on an arm,
// every pair), except the disabled ones: adjacent
// links (robots/pair_filter.h), rigidly attached links (rigidLinkPairs) and the pairs listed in
// WorldOptions::disabledPairs (typically an SRDF's <disable_collisions>, read with
// robots::readSrdfDisabledPairs or computed by robots::computeDisabledPairs). A disabled pair
// never reaches the narrow phase.
//
// Names. A robot link is named by its URDF name, a scene link "scene/<link>", an obstacle
// "obstacle/<name>", an attached object "attached/<name>".
//
// Allowed collisions (world_allowed.cpp). allowCollision(a, b) and allowCollisionsWith(a) name
// bodies: a robot link, an attached object ("attached/<name>" or <name>), a scene link
// ("scene/<link>" or <link>), an obstacle ("obstacle/<name>" or <name>; "<id>" also names every
// obstacle "<id>/<k>" of a planning-scene object of several shapes). A name stands for every
// body it names. An allowed pair takes part in no query: isFree, signedDistance, its contacts
// and gradients, and so the clearance and the push-out built on them. WorldOptions::disabledPairs
// (an SRDF's) and disablePair() enter the same table as robot link pairs.
//
// Fixed pairs (World::fixedPairs). A robot link moved by no joint (the root and the links fixed
// to it), or an object attached to one, against a scene link or an obstacle keeps one distance in
// every configuration. Policy: such a pair is NOT dropped silently: it counts in every query like
// any pair unless allowed (a collision is a collision); the world reports each one within
// tol::kFixedPairReportDistance ONCE, on WorldOptions::progress, when the scene, obstacles or
// attached object that brings it is added (or when reports are turned back on:
// setFixedPairReports), naming the pair and how to allow it; the push-out names it when it is
// what blocks (planners/push_out.h).
//
// Attached objects (world_attached.cpp). An Obstacle attached to a robot link moves with it
// (its pose X_LO in the link frame is fixed): it is checked against scenes, obstacles and the
// robot's links except its own link, its touch links and the links rigidly attached to its link
// (with WorldOptions::disableRigid), and against other attached objects not on the same link.
// Its contacts name it "attached/<name>" with linkA (or bodyB.index) the link carrying it, and
// their gradients are those of the witness point fixed on that link. The reach spheres of the link
// grow to hold the object, and scene pieces the reach filter dropped at load that it may reach
// are checked from then on.
//
// Signed distance (per pair of convex pieces the contract of deep/signed_distance.h, minimized
// over pieces and pairs). For a pair (A, B): A is always a robot link; B is a robot link (self pair, B's link
// index > A's) or a world body. distance > 0 is the distance, < 0 minus the penetration depth;
// normal is unit and points from A towards B; pointB - pointA = distance * normal (world frame).
//
// Gradient (TrajOpt, Schulman et al. 2014): with the witness points fixed on their links,
//     d distance / dq = normal^T (J_B(pointB) - J_A(pointA)),
// J_X(p) the 3 x nq translational Jacobian of the point p moving with link X (kinematics.h); for a
// robot-world pair only A moves: -normal^T J_A(pointA). So moving q along +gradient increases
// the distance (pulls out of a collision). It is the exact derivative where the distance is
// differentiable (a unique closest pair and witness features that do not change); at contact
// changes, between faces parallel to each other, or where two pairs tie, it is one of the
// one-sided derivatives.
//
// Threads. Queries are const and may run concurrently on one World from any number of threads.
// Each thread uses its own Context (warm-start caches for every pair, scratch poses, statistics):
// either one made with makeContext() and passed explicitly (the fastest), or the thread's own,
// used by the overloads without a Context (a thread_local table keyed by world, one lookup per
// query). Contexts are never shared between threads; the hot path takes no lock.
// Changes (obstacles, scenes, disabled pairs) may happen while queries run: a change builds a
// new immutable snapshot of the world under a mutex and bumps a generation counter; each query
// reads the counter once (an atomic load) and refreshes its context only when it changed. A query
// that started before a change finishes on the snapshot it started with.
//
// Errors: std::invalid_argument naming the bad value (a configuration of the wrong size or with a
// NaN, naming the variable; an unknown link, obstacle id or scene; a non-finite pose; a bad
// obstacle shape).

#include "deepcheck/checker/broad_phase.h"
#include "deepcheck/checker/tolerances.h"
#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/geometry/signed_distance.h"
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::checker {

namespace detail {
struct WorldState;
}  // namespace detail

/// What a body of a pair is.
struct BodyRef {
  enum class Kind { RobotLink, SceneLink, Obstacle, Attached } kind = Kind::RobotLink;
  /// RobotLink: link index; SceneLink: link index in its scene; Obstacle: id; Attached: the link
  /// carrying it.
  int index = -1;
  /// SceneLink: the scene's index (addScene order); Attached: the object's position in
  /// World::attachedObjects().
  int scene = -1;
  bool operator==(const BodyRef& o) const { return kind == o.kind && index == o.index && scene == o.scene; }
  bool operator!=(const BodyRef& o) const { return !(*this == o); }
};

/// An obstacle: a primitive or a mesh at a pose X_WO in the world.
struct Obstacle {
  std::string name;  ///< reported as "obstacle/<name>"; must not be empty
  /// Box (boxSize: full edge lengths), Sphere (radius), Cylinder (radius, length along z) or
  /// Mesh (meshPath and meshScale, or `mesh` below), in the obstacle's frame O.
  robots::Geometry geometry;
  /// A mesh given in memory (geometry.type == Mesh with an empty meshPath), frame O, metres.
  std::shared_ptr<const robots::TriangleMesh> mesh;
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();

  static Obstacle box(const std::string& name, const Eigen::Vector3d& size, const Eigen::Isometry3d& X_WO);
  static Obstacle sphere(const std::string& name, double radius, const Eigen::Isometry3d& X_WO);
  static Obstacle cylinder(const std::string& name, double radius, double length, const Eigen::Isometry3d& X_WO);
  static Obstacle meshFile(const std::string& name, const std::string& path, const Eigen::Isometry3d& X_WO,
                           const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());
  static Obstacle fromMesh(const std::string& name, robots::TriangleMesh mesh, const Eigen::Isometry3d& X_WO);
};

/// One pair's signed distance (see the header comment for the conventions).
struct Contact {
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, from A towards B, world frame
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();   ///< witness on A, world frame
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();   ///< witness on B, world frame
  int linkA = -1;                                     ///< robot link of A (carrying it, if attached)
  BodyRef bodyB;
  std::string nameA;  ///< link name or "attached/<name>"
  std::string nameB;  ///< link name, "attached/<name>", "scene/<link>" or "obstacle/<name>"
  geometry::SignedDistanceStatus status = geometry::SignedDistanceStatus::NotConverged;
  /// d distance / dq (numVariables entries) when DistanceOptions::gradient, else empty.
  Eigen::VectorXd gradient;
};

struct DistanceOptions {
  /// Also compute the gradient of each reported distance with respect to q.
  bool gradient = false;
  /// Pairs whose bounding volumes are at least this far apart are not measured. With the default
  /// (infinity) the minimum over all pairs is always found.
  double maxDistance = std::numeric_limits<double>::infinity();
  /// When finite, DistanceResult::contacts lists every body pair (robot link, other body) whose
  /// signed distance is at most this (the minimum over their piece pairs), nearest first.
  double contactMargin = -std::numeric_limits<double>::infinity();
  /// Which pairs take part: robot-scene and robot-obstacle pairs (`world`), robot self pairs
  /// (`self`). Both by default; with one off, the result is the minimum over the other kind only.
  bool worldPairs = true;
  bool selfPairs = true;
  /// Options of the penetration depth: the method and its settings.
  geometry::PenetrationOptions penetration;
};

struct DistanceResult {
  /// False when no pair was within maxDistance (or the world has no pair at all); `closest` is
  /// then default (distance +infinity).
  bool found = false;
  Contact closest;
  std::vector<Contact> contacts;  ///< see DistanceOptions::contactMargin
};

/// What World::isClear demands of every checked pair: how far apart it must be (metres). A robot
/// link i, or an object attached to it, and a world body must be farther apart than
/// base + scale * link[i]; robot links a and b (or objects attached to them) farther than
/// base + scale * self(a, b). `link` has robot().numLinks() entries; `self` is numLinks x numLinks
/// and only the entries of checked pairs are read. Every demand must be finite and >= 0.
/// A motion validator asks, at the middle of a sub-motion, for more than each pair can move over
/// its half (planners/certified_motion_validator.h).
struct ClearanceDemand {
  double base = 0.0;
  double scale = 1.0;
  Eigen::VectorXd link;
  Eigen::MatrixXd self;
};

/// What World::certifyMotion found.
struct MotionCertificate {
  enum class Verdict {
    Certified,  ///< every configuration of the motion keeps every pair clear (proven)
    Collides,   ///< a configuration of the motion has a pair within the threshold (found)
    Unproven,   ///< neither, down to tol::kCertifiedResolution or tol::kCertifiedMaxTests
  };
  Verdict verdict = Verdict::Unproven;
  int configurations = 0;  ///< configurations tested (one per sub-motion examined)
  bool certified() const { return verdict == Verdict::Certified; }
};

/// Counters of one Context (cumulative; reset with Context::resetStats()).
struct QueryStats {
  std::uint64_t queries = 0;
  std::uint64_t linkCandidates = 0;   ///< (robot link, world piece or robot link) pairs from the
                                      ///< broad phase
  std::uint64_t pieceTests = 0;       ///< piece pairs whose bounding volumes were compared
  std::uint64_t narrowPhase = 0;      ///< geometry::overlaps / geometry::signedDistance calls
  std::uint64_t selfNarrowPhase = 0;  ///< the part of narrowPhase on self pairs
  std::uint64_t certifiedSelf = 0;    ///< isFree: self link pairs skipped because q lies in a
                                      ///< cell of their grid certified free (world.cpp summary)
  std::uint64_t centroidInside = 0;   ///< isFree: the part of narrowPhase decided without GJK,
                                      ///< a robot piece's centroid inside a world piece
  std::uint64_t enclosedAgain = 0;    ///< isFree: the part of narrowPhase decided without GJK,
                                      ///< the four vertex pairs that enclosed the origin when the
                                      ///< pair last overlapped enclosing it again
                                      ///< (geometry::enclosesOrigin)
  std::uint64_t fullDepth = 0;        ///< signedDistance: overlapping pairs whose one-walk depth
                                      ///< could beat the best, measured again with all restarts
  std::uint64_t batchCertified = 0;   ///< isFreeBatch: configurations its bound stage certified
                                      ///< free (counted in queries, no isFree call)
};

/// How a World is built.
struct WorldOptions {
  /// Where progress lines of the construction steps that run past tol::kProgressQuietSeconds go
  /// (the robot's pieces, self-pair grids, scenes and obstacles); nullptr: nowhere. A quick load
  /// prints nothing.
  std::ostream* progress = &std::cerr;
  /// Cylinder prisms and how meshes become pieces. An empty `geometry.decomposer` means the
  /// default, robots::meshDecomposer: convex decomposition (decomposition/decomposition.h) with
  /// `decomposition` parameters, through the on-disk cache in `decompositionCacheDir` ("" = the
  /// default directory, decomposition/cache.h), unless `decompose` is false (then one convex hull
  /// per mesh).
  robots::CollisionGeometryOptions geometry;
  bool decompose = true;
  deepcheck::decomposition::DecompositionParams decomposition;
  std::string decompositionCacheDir;
  /// Disable self pairs of adjacent links (robots::adjacentLinkPairs: joined by a joint, or
  /// through links without geometry only).
  bool disableAdjacent = true;
  /// Disable self pairs of rigidly attached links (rigidLinkPairs: joined by fixed joints only;
  /// their relative pose never changes, so they are always or never in collision).
  bool disableRigid = true;
  /// More self pairs to disable, e.g. an SRDF's (robots::readSrdfDisabledPairs); the reasons are
  /// not used. A pair naming a link the robot lacks is an error (robots::checkDisabledPairs).
  std::vector<robots::DisabledPair> disabledPairs;
  /// Scene pieces farther than this from every reach sphere are dropped, and so are the self
  /// pairs of links whose reach spheres stay farther apart than this (metres, >= 0; infinity
  /// keeps everything). Distances below it are exact.
  double reachMargin = tol::kDefaultReachMargin;
  /// Which world pieces may be near a robot link (broad_phase.h): one of the World's own broad
  /// phases, or, when externalBroadPhase is set, the trees it builds (then `broadPhase` is not
  /// used). Neither changes an answer.
  BroadPhase broadPhase = BroadPhase::AabbTree;
  std::shared_ptr<const PieceTreeFactory> externalBroadPhase;
};

/// A scene and where it goes: World::addScene takes the loaded model and this placement;
/// loaders that read the model from a file (planners::loadWorld) take the URDF from `urdf`.
struct SceneSpec {
  /// The scene's URDF file (not used by World::addScene, which is given the model).
  std::string urdf;
  /// Joint values of the scene (its numVariables()); empty: its default configuration.
  Eigen::VectorXd q;
  /// Used as the scene's base pose when overridePose; otherwise the model's own basePose().
  bool overridePose = false;
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();

  SceneSpec() = default;
  SceneSpec(std::string path) : urdf(std::move(path)) {}  // NOLINT: implicit on purpose
  SceneSpec(const char* path) : urdf(path) {}             // NOLINT
  SceneSpec(std::string path, const Eigen::Isometry3d& pose) : urdf(std::move(path)), overridePose(true), X_WS(pose) {}
};

/// How World::attach places an object on a link.
struct AttachOptions {
  /// Robot links the object may touch (its own link always may).
  std::vector<std::string> touchLinks;
  /// False: Obstacle::X_WO is the object's pose in the link frame (X_LO). True: it is its pose in
  /// the world with the robot at `q` (empty: the default configuration).
  bool worldFrame = false;
  Eigen::VectorXd q;
};

/// An attached object as the world holds it (World::attachedObjects).
struct AttachedObjectInfo {
  Obstacle object;  ///< as given; X_WO as given
  std::string link;
  Eigen::Isometry3d X_LO = Eigen::Isometry3d::Identity();  ///< its pose in the link frame
  std::vector<std::string> touchLinks;
  std::vector<robots::CollisionPiece> pieces;  ///< X_LP: pose of the piece in the link frame
};

/// Placement of a MoveIt planning scene (World::addPlanningScene).
struct PlanningSceneOptions {
  /// Scene frame names mapped to robot links (e.g. base_link -> panda_link0).
  robots::FrameAliases frameAliases;
  /// Robot configuration at which the objects' frames are posed; empty: the default one.
  Eigen::VectorXd q;
};

class World {
 public:
  using Options = WorldOptions;

  /// Per-thread query state: warm-start caches (one geometry::PairCache per piece pair), scratch
  /// poses and statistics. Made by World::makeContext(); bound to that world (using it with
  /// another is an error) and must not be used after the world is destroyed; movable, not
  /// copyable; must not be used by two threads at once.
  class Context {
   public:
    Context(Context&&) noexcept;
    Context& operator=(Context&&) noexcept;
    ~Context();
    const QueryStats& stats() const;
    void resetStats();
    /// Forget every warm start (the next queries are cold).
    void resetCaches();
    struct Impl;  ///< opaque (world_queries_internal.h)

   private:
    friend class World;
    explicit Context(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
  };

  /// A world with `robot` and nothing else. Meshes are loaded and decomposed here.
  explicit World(robots::RobotModel robot, const WorldOptions& options = WorldOptions());
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  /// Adds a scene; returns its index. Its pieces are posed and filtered by reach here.
  int addScene(robots::RobotModel scene, const SceneSpec& placement = SceneSpec());
  int addScene(robots::RobotModel scene, const Eigen::Isometry3d& X_WS);
  /// Adds every shape of a MoveIt planning scene as an obstacle named "<id>" (an object with one
  /// shape) or "<id>/<k>" (its k-th shape), posed by robots::shapeWorldPoses; returns their ids in
  /// file order. Then attaches its attached objects (each shape an object named as above, posed
  /// at options.q, with its touch links) and allows its allowed collisions
  /// (world_planning_scene.cpp).
  std::vector<int> addPlanningScene(const robots::PlanningScene& scene, const PlanningSceneOptions& options = {});

  /// Adds an obstacle; returns its id (never reused).
  int addObstacle(const Obstacle& obstacle);
  /// Adds several obstacles at once, all or none (a bad one throws before any is added); returns
  /// their ids in order. One change of the world however many there are: adding n obstacles
  /// one by one rebuilds the broad phase n times, adding them together once.
  std::vector<int> addObstacles(const std::vector<Obstacle>& obstacles);
  /// Throws std::invalid_argument for an unknown id.
  void removeObstacle(int id);
  void setObstaclePose(int id, const Eigen::Isometry3d& X_WO);
  /// Ids of the current obstacles, increasing.
  std::vector<int> obstacleIds() const;

  /// Disables one more self pair (by link names).
  void disablePair(const std::string& linkA, const std::string& linkB);

  // --- allowed collisions (header comment) --------------------------------------------------

  /// Allows bodies named a and b to touch ("*" for either: allowCollisionsWith the other). Throws
  /// std::invalid_argument naming an unknown name and its near matches.
  void allowCollision(const std::string& a, const std::string& b);
  /// Allows the bodies named `name` to touch anything.
  void allowCollisionsWith(const std::string& name);
  /// The allowed pairs as given (first < second), then ("name", "*") for each allowCollisionsWith.
  std::vector<std::pair<std::string, std::string>> allowedCollisions() const;
  /// True when every body named a may touch every body named b (b "*": a was given to
  /// allowCollisionsWith). Throws for an unknown name, as allowCollision.
  bool collisionAllowed(const std::string& a, const std::string& b) const;

  /// The pairs that no joint can change (header comment) within `maxDistance` of each other and
  /// not allowed, as contacts at the default configuration, nearest first.
  std::vector<Contact> fixedPairs(double maxDistance = tol::kFixedPairReportDistance) const;
  /// Off: changes report no fixed pair (a loader adding scenes, then allowing collisions, turns
  /// them off meanwhile). On: reports at once those not reported yet, then at every change.
  /// Returns the previous setting. On by default.
  bool setFixedPairReports(bool on);

  // --- attached objects (header comment) -----------------------------------------------------

  /// Attaches `object` to robot link `link` (options: its frame, touch links). Throws
  /// std::invalid_argument for an unknown link or touch link, a name already attached, or a bad
  /// shape, naming it.
  void attach(const std::string& link, const Obstacle& object, const AttachOptions& options = {});
  /// Attaches obstacle `id` (removed from the obstacles) where it is in the world with the robot at
  /// options.q; options.worldFrame is ignored.
  void attachObstacle(int id, const std::string& link, const AttachOptions& options = {});
  /// Detaches the object `name`: with keepAsObstacle it becomes an obstacle where it is with the
  /// robot at q (empty: the default configuration) and its id is returned; otherwise it is
  /// removed and -1 returned.
  int detach(const std::string& name, bool keepAsObstacle = true, const Eigen::VectorXd& q = Eigen::VectorXd());
  std::vector<AttachedObjectInfo> attachedObjects() const;

  // --- queries -----------------------------------------------------------------------------

  Context makeContext() const;

  /// True when no allowed pair overlaps (touching counts as overlap). Stops at the first overlap.
  bool isFree(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context) const;
  bool isFree(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  /// isFree of each column of qs (the robot's variables x n, 1 <= n <= 8) into free[0 .. n):
  /// always free[i] == isFree(qs.col(i)). Forward kinematics of all columns at once, then a bound
  /// stage across them (AVX2 when the processor has it): a configuration whose bounding volumes
  /// (link and piece spheres, piece oriented boxes) are apart from everything they are checked
  /// against, by a margin that covers the rounding (tol::kBatchBoundRelative), is free; every
  /// other is answered by isFree (world_batch.cpp). Throws std::invalid_argument naming the sizes for a qs of the wrong
  /// shape, and as isFree for a configuration isFree throws for (the columns before it are
  /// answered then).
  void isFreeBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* free, Context& context) const;
  void isFreeBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* free) const;

  /// True when every checked pair is farther apart than `demand` asks (strictly): isFree with each
  /// robot piece grown by its pair's demand, at the same cost. All demands 0 is isFree. Throws
  /// std::invalid_argument for a demand of the wrong size, negative or not finite.
  bool isClear(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context, const ClearanceDemand& demand) const;
  bool isClear(const Eigen::Ref<const Eigen::VectorXd>& q, const ClearanceDemand& demand) const;

  /// isClear of each column of qs (as isFreeBatch: 1 to 8 columns) into clear[0 .. n): always
  /// clear[i] == isClear(qs.col(i), demand). isFreeBatch's bound stage with every bounding volume
  /// grown by its pair's demand answers the configurations it certifies; isClear every other.
  /// Throws like isFreeBatch and isClear.
  void isClearBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* clear, Context& context,
                    const ClearanceDemand& demand) const;
  void isClearBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* clear, const ClearanceDemand& demand) const;

  /// Certifies the straight motion q(t) = q1 + t dq, t in [0, 1] (world_motion.cpp). `motion`
  /// bounds how far each pair moves over the whole motion (link[i]: robot link i against the
  /// world; self(a, b): links a and b relatively; metres; its `scale` is not used) and `base` is
  /// the clearance every configuration must keep (0: collision free). A sub-motion with middle tm
  /// and half length h is certified when every pair is farther apart than base + h times its
  /// bound at q(tm) (isClear). Otherwise a pair within base at q(tm) is a collision, and each
  /// nearer pair's distance d proves it clear within (d - base) / (its margin - base) of h around
  /// tm: the two ends outside that are examined next, with those pairs only. Sub-motions are
  /// visited level by level, so the configurations tested first are spread along the motion.
  /// q1 is assumed valid. Throws like isClear, and for a q1 or dq of the wrong size.
  MotionCertificate certifyMotion(const Eigen::Ref<const Eigen::VectorXd>& q1,
                                  const Eigen::Ref<const Eigen::VectorXd>& dq, const ClearanceDemand& motion,
                                  Context& context) const;
  MotionCertificate certifyMotion(const Eigen::Ref<const Eigen::VectorXd>& q1,
                                  const Eigen::Ref<const Eigen::VectorXd>& dq, const ClearanceDemand& motion) const;

  /// The minimum signed distance over allowed pairs, its pair, witnesses, normal, optionally its
  /// gradient and the contact list.
  DistanceResult signedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context,
                                const DistanceOptions& options = {}) const;
  DistanceResult signedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const DistanceOptions& options = {}) const;

  // --- body-level signed distance (deepcheck/checker/body_distance.h) ----------------------

  /// Defined in deepcheck/checker/body_distance.h (include it to call bodySignedDistance).
  struct BodyDistanceOptions;
  struct BodyContact;
  /// The signed distance of two whole bodies, each the union of its convex pieces, at q: a is a
  /// robot link or an attached object, b any body (body_distance.h has the contract).
  BodyContact bodySignedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const BodyRef& a, const BodyRef& b) const;
  BodyContact bodySignedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const BodyRef& a, const BodyRef& b,
                                 const BodyDistanceOptions& options) const;

  // --- description -------------------------------------------------------------------------

  const robots::RobotModel& robot() const;
  int numScenes() const;
  const robots::RobotModel& scene(int index) const;
  /// The joint values the scene is fixed at.
  const Eigen::VectorXd& sceneConfiguration(int index) const;
  /// The obstacle as given (pose updated by setObstaclePose).
  Obstacle obstacle(int id) const;

  /// The convex pieces the queries use for robot link `link`, in the link frame (X_LP); empty for
  /// a link without geometry; objects attached to it are not among them (attachedObjects()). For
  /// display and export (deepcheck/viewer/html_view.h). Defined in world_pieces.cpp.
  std::vector<robots::CollisionPiece> linkPieces(int link) const;
  /// A scene or obstacle piece as the queries use it: X_LP is its pose in the world.
  struct WorldPieceRef {
    BodyRef body;
    robots::CollisionPiece piece;
  };
  /// Every scene piece kept by the reach filter and every obstacle piece, posed in the world.
  std::vector<WorldPieceRef> worldPieces() const;

  /// Per robot link: a bound on the distance from the link's origin to any point of the pieces it
  /// carries, its own and those of objects attached to it (their bounding spheres); -1 for a link
  /// that carries none. Changes with attach() and detach(): see version().
  std::vector<double> linkExtents() const;
  /// A number that changes whenever the world does (scenes, obstacles, attached objects, allowed
  /// collisions), so that what a caller derived from it can be refreshed.
  std::uint64_t version() const;

  /// Self pairs checked, as (link, link) with the first index smaller.
  std::vector<std::pair<int, int>> allowedSelfPairs() const;
  /// The name of a body ("scene/<link>", "obstacle/<name>" or the link name).
  std::string bodyName(const BodyRef& body) const;

  struct Summary {
    int robotLinks = 0;  ///< all links
    int robotLinksWithGeometry = 0;
    int robotPieces = 0;
    int selfPairs = 0;  ///< link pairs checked
    int selfPiecePairs = 0;
    int disabledAdjacent = 0;  ///< link pairs with geometry disabled as adjacent
    int disabledRigid = 0;     ///< ... as rigidly attached (and not adjacent)
    int disabledByUser = 0;    ///< ... by WorldOptions::disabledPairs or disablePair()
    int unreachablePairs = 0;  ///< ... not checked: they can never come within reachMargin
    int scenes = 0;
    int sceneLinksWithGeometry = 0;
    int scenePiecesKept = 0;
    int scenePiecesDropped = 0;
    int obstacles = 0;
    int obstaclePieces = 0;
    int attachedObjects = 0;
    int attachedPieces = 0;
    int allowedCollisions = 0;  ///< entries of the allowed-collision table (SRDF pairs included)
    /// Largest amount by which a piece may stick out of the original geometry (cylinder prisms,
    /// convex decomposition's concavity); NaN when a custom decomposer makes it unknown. Metres.
    double geometryExcess = 0.0;
  };
  Summary summaryCounts() const;
  /// Human-readable summary: links, pieces, scene pieces kept and dropped, pairs checked.
  std::string summary() const;

  /// The world's shared state; its type is internal to the library (checker/src/world_internal.h).
  const std::shared_ptr<detail::WorldState>& internalState() const { return state_; }

 private:
  /// The changes made under the world's lock; the public functions then report the new fixed
  /// pairs (world_fixed_pairs.cpp), which queries the world and so needs the lock released.
  int addSceneLocked(robots::RobotModel scene, const SceneSpec& placement);
  std::vector<int> addObstaclesLocked(const std::vector<Obstacle>& obstacles);

  std::shared_ptr<detail::WorldState> state_;
};

/// True when no joint moves `link` relative to the robot's root: every joint between them is
/// fixed (or locked). Such a link keeps its pose in every configuration (world_fixed_pairs.cpp).
bool movedByNoJoint(const robots::RobotModel& model, int link);

/// Link pairs (i < j), both with geometry (`hasGeometry[link]`), joined by fixed joints only: their
/// relative pose never changes.
std::vector<std::pair<int, int>> rigidLinkPairs(const robots::RobotModel& model, const std::vector<bool>& hasGeometry);

}  // namespace deepcheck::checker
