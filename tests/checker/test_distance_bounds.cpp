// The lower bounds World::signedDistance prunes with, and the query itself, against exact
// signed distances: every bound must stay below the pair's signed distance however deep the
// pieces overlap, up to one inside the other; and the world's minimum must equal the brute-force
// minimum over all piece pairs, obstacles big enough to swallow a link included.

#include "checker_test_util.h"

#include "aabb_tree.h"
#include "world_internal.h"
#include "world_queries_internal.h"

#include "deepcheck/geometry/signed_distance.h"
#include "deepcheck/fcl_reference/fcl_broad_phase.h"
#include "deepcheck/robots/kinematics.h"

#include "geometry/shapes.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <memory>
#include <random>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;
using geometry::testing::makePose;
using geometry::testing::randomRotation;
using geometry::testing::randomUnit;

namespace {

/// Rounding allowed when a bound is compared with an exact signed distance, relative to the
/// pair's size plus its distance from the origin (metres per metre).
constexpr double kBoundRoundoff = 1e-12;

/// Agreement required between World::signedDistance and the brute-force minimum, relative to
/// max(1 m, |distance|): both run the same exact pair query, from different warm starts.
constexpr double kWorldAgreement = 1e-9;

/// The shape kinds of the world's pieces: box, sphere (a point core), cylinder (a prism core),
/// capsule (a segment core) and a mesh piece (a random hull).
std::shared_ptr<const geometry::ConvexPolytope> randomCore(std::mt19937& rng, int kind, double size, double* radius) {
  std::uniform_real_distribution<double> u(0.3, 1.0);
  *radius = 0.0;
  switch (kind) {
    case 0:
      return std::make_shared<geometry::ConvexPolytope>(
          geometry::ConvexPolytope::box(2.0 * size * Eigen::Vector3d(u(rng), u(rng), u(rng))));
    case 1:
      *radius = size;
      return std::make_shared<geometry::ConvexPolytope>(
          geometry::ConvexPolytope::fromPoints({Eigen::Vector3d::Zero()}));
    case 2:
      return std::make_shared<geometry::ConvexPolytope>(
          geometry::ConvexPolytope::fromPoints(geometry::testing::prismPoints(size * u(rng), 2 * size * u(rng), 16)));
    case 3:
      *radius = 0.3 * size * u(rng);
      return std::make_shared<geometry::ConvexPolytope>(
          geometry::ConvexPolytope::fromPoints({Eigen::Vector3d(0, 0, -size), Eigen::Vector3d(0, 0, size)}));
    default:
      return std::make_shared<geometry::ConvexPolytope>(geometry::ConvexPolytope::fromPoints(
          geometry::testing::ellipsoidPoints(rng, 24, size * Eigen::Vector3d(u(rng), u(rng), u(rng)))));
  }
}

/// A random piece of a random kind, posed as the world poses its pieces (box, sphere, oriented box).
detail::WorldPiece randomPiece(std::mt19937& rng, double size, const Eigen::Vector3d& at) {
  const int kind = std::uniform_int_distribution<int>(0, 4)(rng);
  robots::CollisionPiece p;
  p.core = randomCore(rng, kind, size, &p.radius);
  return detail::makeWorldPiece(p, makePose(randomRotation(rng), at), 0, 0);
}

geometry::SignedDistanceResult exact(const detail::WorldPiece& a, const detail::WorldPiece& b) {
  return geometry::signedDistance(detail::shapeOf(a), a.X_WP, detail::shapeOf(b), b.X_WP);
}

enum Regime { kSeparated, kTouching, kShallow, kDeep, kContained, kRegimes };

/// Two random pieces in one of the regimes: B apart from A, touching it, overlapping it by a
/// little or a lot, or A (small) wholly inside B (big).
std::pair<detail::WorldPiece, detail::WorldPiece> randomPair(std::mt19937& rng, Regime regime) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Vector3d origin = 10.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
  if (regime == kContained) {
    // A small piece wholly inside the big one's inner ball (drawn again until it fits).
    for (;;) {
      detail::WorldPiece big = randomPiece(rng, 1.0, origin);
      detail::WorldPiece small = randomPiece(rng, 0.02, big.center_W + 0.02 * randomUnit(rng));
      const double reach = (small.center_W - big.center_W).norm() + small.sphereRadius;
      if (reach < big.core->insideRadius() + big.radius) return {small, big};
    }
  }
  const detail::WorldPiece a = randomPiece(rng, 0.05 + 0.5 * u(rng), origin);
  // Separated: B's centre beyond both bounding spheres; deep: inside A's inner ball.
  const double inner = a.core->insideRadius() + a.radius;
  const double offset = regime == kSeparated ? a.sphereRadius + 1.0 + u(rng)
                        : regime == kDeep    ? 0.9 * u(rng) * inner
                                             : 0.5;
  detail::WorldPiece b = randomPiece(rng, 0.05 + 0.5 * u(rng), a.center_W + offset * randomUnit(rng));
  if (regime == kTouching || regime == kShallow) {
    // Move B along the normal until it touches A, then (shallow) a little into it.
    const geometry::SignedDistanceResult r = exact(a, b);
    const double into = regime == kShallow ? 0.02 * u(rng) * a.sphereRadius : 0.0;
    robots::CollisionPiece p{b.core, b.radius, b.X_WP, ""};
    p.X_LP.translation() -= (r.distance + into) * r.normal;
    b = detail::makeWorldPiece(p, Eigen::Isometry3d::Identity(), 0, 0);
  }
  return {a, b};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(distance_bounds)

// Every pruning bound of the query (sphere to box, sphere to sphere, support functions, the
// tree's nodes) is at most the exact signed distance, in every regime and for every shape kind;
// the centres' bound the query keeps as an upper bound is at least it.
BOOST_AUTO_TEST_CASE(every_bound_is_a_bound) {
  std::mt19937 rng(3901);
  int counted[kRegimes] = {};
  for (int trial = 0; trial < 5000; ++trial) {
    const auto regime = static_cast<Regime>(trial % kRegimes);
    const auto [a, b] = randomPair(rng, regime);
    const double sd = exact(a, b).distance;
    const double slack = kBoundRoundoff * (a.sphereRadius + b.sphereRadius + a.center_W.norm() + b.center_W.norm());
    const bool inRegime = regime == kSeparated ? sd > 0 : regime == kTouching ? std::abs(sd) <= 1e3 * slack : sd < 0;
    BOOST_TEST_REQUIRE(inRegime, "trial " << trial << " regime " << regime << ": sd " << sd);
    ++counted[regime];

    const double sphereBox = b.box.signedDistance(a.center_W) - a.sphereRadius;
    const double boxSphere = a.box.signedDistance(b.center_W) - b.sphereRadius;
    const double spheres = (a.center_W - b.center_W).norm() - a.sphereRadius - b.sphereRadius;
    BOOST_TEST(sphereBox <= sd + slack,
               "trial " << trial << " regime " << regime << ": sphere-box " << sphereBox << " > sd " << sd);
    BOOST_TEST(boxSphere <= sd + slack,
               "trial " << trial << " regime " << regime << ": box-sphere " << boxSphere << " > sd " << sd);
    BOOST_TEST(spheres <= sd + slack,
               "trial " << trial << " regime " << regime << ": spheres " << spheres << " > sd " << sd);
    const Eigen::Vector3d u = randomUnit(rng);
    for (const Eigen::Vector3d& dir : {u, Eigen::Vector3d((b.center_W - a.center_W).normalized())}) {
      if (!dir.allFinite()) continue;
      const double support = detail::supportLowerBound(*a.core, a.X_WP, a.radius, *b.core, b.X_WP, b.radius, dir);
      BOOST_TEST(support <= sd + slack,
                 "trial " << trial << " regime " << regime << ": support " << support << " > sd " << sd);
    }
    const double upper = (a.center_W - b.center_W).norm() - a.radius - b.radius;
    BOOST_TEST(upper >= sd - slack,
               "trial " << trial << " regime " << regime << ": centres " << upper << " < sd " << sd);
  }
  for (int r = 0; r < kRegimes; ++r) BOOST_TEST(counted[r] == 1000);
}

// The tree's branch and bound visits, with bound() the exact minimum plus rounding, the piece
// that attains it, and every lower bound it reports is at most that piece's exact distance:
// a query sphere deep inside a big piece's box must not be pruned by a shallow neighbour.
BOOST_AUTO_TEST_CASE(tree_visits_the_deepest_piece) {
  std::mt19937 rng(3902);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<detail::WorldPiece> pieces;
    std::vector<Aabb> boxes;
    const int n = 2 + trial % 7;
    for (int k = 0; k < n; ++k) {
      const double size = k == 0 ? 1.5 : 0.05 + 0.2 * (u(rng) + 1.0);
      pieces.push_back(randomPiece(rng, size, Eigen::Vector3d(u(rng), u(rng), u(rng))));
      boxes.push_back(pieces.back().box);
    }
    const detail::WorldPiece query = randomPiece(rng, 0.1, 0.5 * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    double minimum = std::numeric_limits<double>::infinity();
    std::vector<double> sd;
    for (const detail::WorldPiece& p : pieces) {
      sd.push_back(exact(query, p).distance);
      minimum = std::min(minimum, sd.back());
    }
    const double slack = kBoundRoundoff * 10.0;
    bool reachedMinimum = false;
    AabbTree tree(boxes);
    tree.visitNear(
        query.center_W, query.sphereRadius, [&] { return minimum + slack; },
        [&](int item, double lowerBound) {
          BOOST_TEST(lowerBound <= sd[item] + slack,
                     "trial " << trial << " piece " << item << ": " << lowerBound << " > " << sd[item]);
          reachedMinimum = reachedMinimum || sd[item] == minimum;
        });
    BOOST_TEST(reachedMinimum, "trial " << trial << ": the piece at the minimum " << minimum << " was pruned");
  }
}

namespace {

/// The minimum signed distance over every piece pair the world checks (robot-world pairs and
/// the allowed self pairs), each measured afresh; per body pair too, keyed (link, body).
struct BruteForce {
  double minimum = std::numeric_limits<double>::infinity();
  std::map<std::tuple<int, int, int, int>, double> bodies;
};

/// The key of a body pair: the robot link, then the other body's kind, index and scene.
std::tuple<int, int, int, int> bodyPair(int link, const BodyRef& body) {
  return {link, static_cast<int>(body.kind), body.index, body.scene};
}

BruteForce bruteForce(const World& world, const Eigen::VectorXd& q) {
  const robots::RobotModel& model = world.robot();
  const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, q);
  std::vector<std::vector<robots::CollisionPiece>> links(model.numLinks());
  for (int l = 0; l < model.numLinks(); ++l) links[l] = world.linkPieces(l);
  BruteForce out;
  auto measure = [&](int link, const robots::CollisionPiece& p, const BodyRef& body, const robots::CollisionPiece& o,
                     const Eigen::Isometry3d& X_WO) {
    const double sd = geometry::signedDistance(geometry::ConvexShape{p.core.get(), p.radius}, X_WL[link] * p.X_LP,
                                               geometry::ConvexShape{o.core.get(), o.radius}, X_WO)
                          .distance;
    out.minimum = std::min(out.minimum, sd);
    auto [it, added] = out.bodies.emplace(bodyPair(link, body), sd);
    if (!added) it->second = std::min(it->second, sd);
  };
  const std::vector<World::WorldPieceRef> world_pieces = world.worldPieces();
  for (int l = 0; l < model.numLinks(); ++l) {
    for (const robots::CollisionPiece& p : links[l]) {
      for (const World::WorldPieceRef& w : world_pieces) measure(l, p, w.body, w.piece, w.piece.X_LP);
    }
  }
  for (const auto& [la, lb] : world.allowedSelfPairs()) {
    BodyRef body;
    body.kind = BodyRef::Kind::RobotLink;
    body.index = lb;
    for (const robots::CollisionPiece& p : links[la]) {
      for (const robots::CollisionPiece& o : links[lb]) measure(la, p, body, o, X_WL[lb] * o.X_LP);
    }
  }
  return out;
}

/// One to four obstacles of every kind around the arm, from 2 cm to big enough to swallow
/// several links (a 1.5 m box, a ball around the base).
void addRandomObstacles(World& world, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 1 + static_cast<int>(4 * u(rng));
  for (int k = 0; k < n; ++k) {
    const double size = 0.02 * std::pow(75.0, u(rng));  // 2 cm to 1.5 m, log-uniform
    const Eigen::Isometry3d X =
        makePose(randomRotation(rng), Eigen::Vector3d(1.2 * u(rng) - 0.6, 1.2 * u(rng) - 0.6, 1.2 * u(rng)));
    const std::string name = "o" + std::to_string(k);
    switch (static_cast<int>(4 * u(rng))) {
      case 0:
        world.addObstacle(Obstacle::box(name, size * Eigen::Vector3d(u(rng) + 0.3, u(rng) + 0.3, u(rng) + 0.3), X));
        break;
      case 1:
        world.addObstacle(Obstacle::sphere(name, 0.5 * size, X));
        break;
      case 2:
        world.addObstacle(Obstacle::cylinder(name, 0.5 * size, size * (u(rng) + 0.3), X));
        break;
      default: {
        robots::TriangleMesh mesh = tetrahedronMesh();
        for (Eigen::Vector3d& v : mesh.vertices) v *= size / 0.3;
        world.addObstacle(Obstacle::fromMesh(name, mesh, X));
      }
    }
  }
}

struct WorldTrials {
  int trials = 0;
  int penetrating = 0;  ///< brute-force minimum below zero
  int swallowed = 0;    ///< ... by more than 10 cm
};

/// World::signedDistance (one context, random configurations and short walks between them, so
/// warm starts are exercised too) against the brute force, in `scenes` random scenes of `perScene`
/// configurations; the contact list (margin 0) against the brute force per body pair.
WorldTrials compareWithBruteForce(const WorldOptions& options, int scenes, int perScene, unsigned seed) {
  World world(armRobot(), options);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(-0.01, 0.01);
  WorldTrials t;
  DistanceOptions withContacts;
  withContacts.contactMargin = 0.0;
  for (int scene = 0; scene < scenes; ++scene) {
    for (int id : world.obstacleIds()) world.removeObstacle(id);
    addRandomObstacles(world, rng);
    auto context = world.makeContext();
    Eigen::VectorXd q = randomConfiguration(world.robot(), rng);
    for (int k = 0; k < perScene; ++k) {
      if (k % 2 == 0) {
        q = randomConfiguration(world.robot(), rng);
      } else {
        for (int v = 0; v < q.size(); ++v) q[v] += step(rng);
      }
      const bool contacts = k % 5 == 0;
      const DistanceResult r = world.signedDistance(q, context, contacts ? withContacts : DistanceOptions());
      const BruteForce b = bruteForce(world, q);
      ++t.trials;
      t.penetrating += b.minimum < 0;
      t.swallowed += b.minimum < -0.1;
      const double tol = kWorldAgreement * std::max(1.0, std::abs(b.minimum));
      BOOST_TEST_REQUIRE(r.found,
                         "scene " << scene << " q " << q.transpose() << ": no pair, brute force " << b.minimum);
      BOOST_TEST_REQUIRE(std::abs(r.closest.distance - b.minimum) <= tol,
                         "scene " << scene << " q " << q.transpose() << ": " << r.closest.distance << " ("
                                  << r.closest.nameA << ", " << r.closest.nameB << "), brute force " << b.minimum);
      BOOST_TEST_REQUIRE(world.isFree(q, context) == (b.minimum > 0), "scene " << scene << " q " << q.transpose());
      if (!contacts) continue;
      std::size_t expected = 0;
      for (const auto& [key, sd] : b.bodies) expected += sd <= 0.0;
      BOOST_TEST_REQUIRE(r.contacts.size() == expected, "scene " << scene << " q " << q.transpose());
      for (const Contact& c : r.contacts) {
        const double sd = b.bodies.at(bodyPair(c.linkA, c.bodyB));
        BOOST_TEST_REQUIRE(std::abs(c.distance - sd) <= tol,
                           c.nameA << " - " << c.nameB << ": " << c.distance << ", brute force " << sd);
      }
    }
  }
  return t;
}

}  // namespace

// 10,000 configurations in 200 random scenes whose obstacles reach from 2 cm to 1.5 m: the
// world's minimum equals the brute-force minimum, no pair is dropped, isFree agrees.
BOOST_AUTO_TEST_CASE(world_equals_brute_force_with_swallowing_obstacles) {
  const WorldTrials t = compareWithBruteForce(testWorldOptions(), 200, 50, 3903);
  BOOST_TEST(t.trials == 10000);
  BOOST_TEST(t.penetrating > 2000);  // the scenes do penetrate, often deeply
  BOOST_TEST(t.swallowed > 500);
}

// The same with the other broad phases: every world piece a candidate, and FCL's tree.
BOOST_AUTO_TEST_CASE(world_equals_brute_force_with_other_broad_phases) {
  for (bool fcl : {false, true}) {
    WorldOptions options = testWorldOptions();
    if (fcl) {
      options.externalBroadPhase = fcl_reference::fclBroadPhase();
    } else {
      options.broadPhase = BroadPhase::None;
    }
    const WorldTrials t = compareWithBruteForce(options, 40, 25, 3904);
    BOOST_TEST(t.swallowed > 50);
  }
}

// The cases that were reported wrong: the arm inside a 0.3 m ball around its base, and inside a
// 1 m box.
BOOST_AUTO_TEST_CASE(arm_inside_a_ball_and_a_box) {
  for (int which = 0; which < 2; ++which) {
    World world(armRobot(), testWorldOptions());
    if (which == 0) {
      world.addObstacle(Obstacle::sphere("ball", 0.3, translation(0, 0, 0)));
    } else {
      world.addObstacle(Obstacle::box("crate", Eigen::Vector3d(1, 1, 1), translation(0, 0, 0.3)));
    }
    const Eigen::VectorXd q = Eigen::VectorXd::Zero(world.robot().numVariables());
    const DistanceResult r = world.signedDistance(q);
    const BruteForce b = bruteForce(world, q);
    BOOST_TEST_REQUIRE(r.found);
    BOOST_TEST(b.minimum < -0.1);
    BOOST_TEST(std::abs(r.closest.distance - b.minimum) <= kWorldAgreement);
  }
}

BOOST_AUTO_TEST_SUITE_END()
