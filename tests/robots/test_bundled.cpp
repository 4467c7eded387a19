// The robot and scenes bundled in robots/data (no ../shared needed): the arm loads with its
// package, its kinematics are the KUKA iiwa 7 R800's link lengths, its meshes are small, closed
// and non-convex, the committed SRDF is what the pair filter computes, and the start and goal
// configurations documented in robots/data/README.md are collision free, 1.5 cm apart.

#include "robots_test_util.h"

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include "deepcheck/geometry/signed_distance.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace deepcheck::robots;

namespace {

const std::string kData = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
const std::string kArmUrdf = kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf";
const std::string kArmSrdf = kData + "/deepcheck_arm/srdf/deepcheck_arm.srdf";

/// Parameters the committed SRDF was generated with (it says so in its comment).
constexpr int kSrdfSamples = 1000000;
constexpr std::uint64_t kSrdfSeed = 1;
/// The regeneration check runs the first kRegenerateSamples of those samples (same seed, so the
/// same configurations): a pair the full run calls Never must be Never here too.
constexpr int kRegenerateSamples = 20000;

/// Lengths are compared to this (metres): the URDF gives them with 3 to 4 digits.
constexpr double kLengthTolerance = 1e-9;

RobotModel loadData(const std::string& path) {
  LoadOptions o;
  o.packageRoots = {kData};
  o.useRosPackagePath = false;
  return RobotModel::fromUrdfFile(path, o);
}

double degrees(double d) { return d * M_PI / 180.0; }

/// A suggested planning problem: robots/data/README.md lists the same numbers.
struct Problem {
  std::string scene;
  std::vector<double> start;
  std::vector<double> goal;
};

const std::vector<double> kStart = {0, -0.4, 0, -1.6, 0, 1.2, 0};
const std::vector<Problem> kProblems = {
    {"table", kStart, {-0.14, 0.61, 0.24, -0.77, -0.14, 1.77, -2.23}},
    {"shelf", kStart, {1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79}},
    {"narrow_passage", kStart, {-0.40, 1.72, -0.40, 1.79, 0.31, 1.50, 0.59}},
};

Eigen::VectorXd vec(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// Clearance of the documented start and goal configurations (robots/data/README.md).
constexpr double kProblemClearance = 0.015;

/// Smallest signed distance between a piece of `a` and a piece of `b`, posed at X_WA and X_WB.
double piecesDistance(const std::vector<CollisionPiece>& a, const Eigen::Isometry3d& X_WA,
                      const std::vector<CollisionPiece>& b, const Eigen::Isometry3d& X_WB) {
  double best = std::numeric_limits<double>::infinity();
  for (const CollisionPiece& pa : a) {
    for (const CollisionPiece& pb : b) {
      const auto r = deepcheck::geometry::signedDistance(
          deepcheck::geometry::ConvexShape{pa.core.get(), pa.radius}, X_WA * pa.X_LP,
          deepcheck::geometry::ConvexShape{pb.core.get(), pb.radius}, X_WB * pb.X_LP);
      best = std::min(best, r.distance);
    }
  }
  return best;
}

/// Tool point: between the fingertips, 12 cm from the flange along the hand's z axis.
const Eigen::Vector3d kToolPoint_H(0, 0, 0.12);

double closedVolume(const TriangleMesh& mesh, bool& closed) {
  std::map<std::pair<int, int>, int> edges;
  double volume6 = 0.0;
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
    volume6 += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  closed = true;
  for (const auto& [e, n] : edges) {
    const auto o = edges.find({e.second, e.first});
    closed = closed && n == 1 && o != edges.end() && o->second == 1;
  }
  return volume6 / 6.0;
}

double hullVolume(const deepcheck::geometry::ConvexPolytope& p) {
  double volume6 = 0.0;
  for (int f = 0; f < p.numFaces(); ++f) {
    const auto face = p.faceVertices(f);
    for (int k = 1; k + 1 < face.size(); ++k) {
      volume6 += p.vertex(face[0]).dot(p.vertex(face[k]).cross(p.vertex(face[k + 1])));
    }
  }
  return volume6 / 6.0;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_bundled)

BOOST_AUTO_TEST_CASE(arm_loads_with_its_package) {
  const RobotModel arm = loadData(kArmUrdf);
  BOOST_TEST(arm.name() == "deepcheck_arm");
  BOOST_TEST(arm.numLinks() == 12);
  BOOST_REQUIRE_EQUAL(arm.numVariables(), 7);
  const std::vector<std::string> names = {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7"};
  BOOST_TEST(arm.variableNames() == names, boost::test_tools::per_element());
  // KUKA LBR iiwa 7 R800 limits: +-170, +-120, +-170, +-120, +-170, +-120, +-175 degrees.
  const double limits[7] = {170, 120, 170, 120, 170, 120, 175};
  for (int v = 0; v < 7; ++v) {
    BOOST_TEST(arm.upperLimits()[v] == degrees(limits[v]), boost::test_tools::tolerance(1e-5));
    BOOST_TEST(arm.lowerLimits()[v] == -arm.upperLimits()[v]);
    BOOST_TEST(arm.joint(arm.variableJoint(v)).velocityLimit > 0.0);
  }
  for (const Link& link : arm.links()) {
    for (const CollisionElement& c : link.collisions) {
      BOOST_TEST(c.geometry.meshUri.rfind("package://deepcheck_arm/meshes/", 0) == 0u);
    }
  }
  BOOST_TEST(arm.link(arm.linkIndex("flange")).collisions.empty());
}

BOOST_AUTO_TEST_CASE(arm_has_the_iiwa_link_lengths) {
  const RobotModel arm = loadData(kArmUrdf);
  const int shoulder = arm.linkIndex("link2"), elbow = arm.linkIndex("link4"), wrist = arm.linkIndex("link6"),
            flange = arm.linkIndex("flange");
  // Straight up at zero: the flange at 0.34 + 0.4 + 0.4 + 0.126.
  const auto X0 = forwardKinematics(arm, Eigen::VectorXd::Zero(7));
  BOOST_TEST((X0[flange].translation() - Eigen::Vector3d(0, 0, 1.266)).norm() < kLengthTolerance);
  std::mt19937 rng(11);
  for (int s = 0; s < 50; ++s) {
    Eigen::VectorXd q(7);
    for (int v = 0; v < 7; ++v) {
      q[v] = std::uniform_real_distribution<double>(arm.lowerLimits()[v], arm.upperLimits()[v])(rng);
    }
    const auto X = forwardKinematics(arm, q);
    BOOST_TEST(std::abs(X[shoulder].translation().norm() - 0.34) < kLengthTolerance);
    BOOST_TEST(std::abs((X[elbow].translation() - X[shoulder].translation()).norm() - 0.40) < kLengthTolerance);
    BOOST_TEST(std::abs((X[wrist].translation() - X[elbow].translation()).norm() - 0.40) < kLengthTolerance);
    BOOST_TEST(std::abs((X[flange].translation() - X[wrist].translation()).norm() - 0.126) < kLengthTolerance);
  }
}

BOOST_AUTO_TEST_CASE(meshes_small_closed_nonconvex) {
  const RobotModel arm = loadData(kArmUrdf);
  std::set<std::string> seen;
  for (const Link& link : arm.links()) {
    for (const CollisionElement& c : link.collisions) {
      if (!seen.insert(c.geometry.meshPath).second) continue;
      const TriangleMesh mesh = loadMesh(c.geometry.meshPath);
      bool closed = false;
      const double volume = closedVolume(mesh, closed);
      const auto hull = deepcheck::geometry::ConvexPolytope::fromPoints(mesh.vertices);
      const double ratio = hullVolume(hull) / volume;
      BOOST_TEST(mesh.triangles.size() <= 400u, c.geometry.meshUri);
      BOOST_TEST(closed, c.geometry.meshUri << " is not closed");
      BOOST_TEST(volume > 0.0, c.geometry.meshUri << " faces inward");
      // Every mesh is non-convex: its hull is at least 10 % larger.
      BOOST_TEST(ratio > 1.1, c.geometry.meshUri << " is (nearly) convex: " << ratio);
    }
  }
  BOOST_TEST(seen.size() == 10u);  // base, link1..7, hand, finger (used by both fingers)
}

BOOST_AUTO_TEST_CASE(srdf_is_what_the_filter_computes) {
  const RobotModel arm = loadData(kArmUrdf);
  const std::vector<DisabledPair> committed = readSrdfDisabledPairs(kArmSrdf);
  checkDisabledPairs(arm, committed, kArmSrdf);
  {
    std::ifstream in(kArmSrdf);
    std::stringstream text;
    text << in.rdbuf();
    BOOST_TEST(text.str().find(std::to_string(kSrdfSamples) + " random samples, seed " + std::to_string(kSrdfSeed)) !=
               std::string::npos);
  }
  PairFilterOptions o;
  o.samples = kRegenerateSamples;
  o.seed = kSrdfSeed;
  const PairFilterResult r = computeDisabledPairs(arm, collisionPieces(arm), o);
  std::map<std::pair<std::string, std::string>, DisableReason> now;
  for (const DisabledPair& p : r.disabled) now[pairKey(p.link1, p.link2)] = p.reason;
  int never = 0;
  for (const DisabledPair& p : committed) {
    const auto k = pairKey(p.link1, p.link2);
    const auto it = now.find(k);
    BOOST_REQUIRE_MESSAGE(it != now.end(), k.first << " - " << k.second << " (" << toString(p.reason)
                                                   << ") is not disabled by the filter now");
    if (p.reason == DisableReason::Never) {
      ++never;
      BOOST_TEST((it->second == DisableReason::Never));
    } else {
      // Adjacent, Default and Always do not depend on the number of samples here.
      BOOST_TEST(toString(it->second) == toString(p.reason));
    }
  }
  // Structural reasons match exactly (both ways).
  for (const DisabledPair& p : r.disabled) {
    if (p.reason == DisableReason::Never) continue;
    bool found = false;
    for (const DisabledPair& c : committed) found = found || pairKey(c.link1, c.link2) == pairKey(p.link1, p.link2);
    BOOST_TEST(found, p.link1 << " - " << p.link2 << " (" << toString(p.reason) << ") missing from the SRDF");
  }
  // Flange (no geometry) makes link7 and hand adjacent.
  BOOST_TEST((now.at(pairKey("link7", "hand")) == DisableReason::Adjacent));
}

BOOST_AUTO_TEST_CASE(srdf_never_pairs_hold_in_a_fresh_sample) {
  const RobotModel arm = loadData(kArmUrdf);
  const auto pieces = collisionPieces(arm);
  std::set<std::pair<std::string, std::string>> never;
  for (const DisabledPair& p : readSrdfDisabledPairs(kArmSrdf)) {
    if (p.reason == DisableReason::Never) never.insert(pairKey(p.link1, p.link2));
  }
  std::mt19937 rng(4242);
  int collisions = 0;
  std::vector<Eigen::Isometry3d> X;
  for (int s = 0; s < 5000; ++s) {
    Eigen::VectorXd q(7);
    for (int v = 0; v < 7; ++v) {
      q[v] = std::uniform_real_distribution<double>(arm.lowerLimits()[v], arm.upperLimits()[v])(rng);
    }
    forwardKinematics(arm, q, X);
    for (const auto& [i, j] : collidingLinkPairs(arm, pieces, X)) {
      const auto k = pairKey(arm.link(i).name, arm.link(j).name);
      BOOST_TEST(never.count(k) == 0u, k.first << " - " << k.second << " is Never but collides");
      collisions += arm.linkIndex("link5") == i && arm.linkIndex("link7") == j;
    }
  }
  BOOST_TEST(collisions > 0);  // the sample does find the wrist folding onto the forearm
}

BOOST_AUTO_TEST_CASE(scenes_load_as_primitives) {
  const std::map<std::string, int> links = {{"table", 4}, {"shelf", 1}, {"narrow_passage", 2}};
  for (const auto& [name, count] : links) {
    const RobotModel scene = loadData(kData + "/scenes/" + name + ".urdf");
    BOOST_TEST(scene.numLinks() == count, name);
    BOOST_TEST(scene.numVariables() == 0, name);
    for (const Link& link : scene.links()) {
      for (const CollisionElement& c : link.collisions) {
        BOOST_TEST((c.geometry.type != GeometryType::Mesh), name << " " << link.name);
      }
    }
    const auto pieces = collisionPieces(scene);
    int n = 0;
    for (const auto& p : pieces) n += static_cast<int>(p.size());
    BOOST_TEST(n == scene.numCollisionElements(), name);
  }
}

BOOST_AUTO_TEST_CASE(start_and_goal_are_collision_free) {
  const RobotModel arm = loadData(kArmUrdf);
  const auto armPieces = collisionPieces(arm);
  const auto selfPairs = enabledLinkPairs(arm, armPieces, readSrdfDisabledPairs(kArmSrdf));
  BOOST_TEST(!selfPairs.empty());
  const int hand = arm.linkIndex("hand");
  for (const Problem& problem : kProblems) {
    const RobotModel scene = loadData(kData + "/scenes/" + problem.scene + ".urdf");
    const auto scenePieces = collisionPieces(scene);
    const auto X_S = forwardKinematics(scene, Eigen::VectorXd::Zero(0));
    for (const auto* which : {&problem.start, &problem.goal}) {
      const std::string label = problem.scene + (which == &problem.start ? " start" : " goal");
      const Eigen::VectorXd q = vec(*which);
      BOOST_REQUIRE_EQUAL(q.size(), 7);
      BOOST_TEST(((q.array() >= arm.lowerLimits().array()).all() && (q.array() <= arm.upperLimits().array()).all()),
                 label << " is outside the joint limits");
      const auto X = forwardKinematics(arm, q);
      for (const auto& [i, j] : selfPairs) {
        BOOST_TEST(!piecesOverlap(armPieces[i], X[i], armPieces[j], X[j]),
                   label << ": " << arm.link(i).name << " hits " << arm.link(j).name);
        BOOST_TEST(piecesDistance(armPieces[i], X[i], armPieces[j], X[j]) >= kProblemClearance,
                   label << ": " << arm.link(i).name << " is too close to " << arm.link(j).name);
      }
      for (int a = 0; a < arm.numLinks(); ++a) {
        for (int s = 0; s < scene.numLinks(); ++s) {
          BOOST_TEST(!piecesOverlap(armPieces[a], X[a], scenePieces[s], X_S[s]),
                     label << ": " << arm.link(a).name << " hits " << scene.link(s).name);
          BOOST_TEST(piecesDistance(armPieces[a], X[a], scenePieces[s], X_S[s]) >= kProblemClearance,
                     label << ": " << arm.link(a).name << " is too close to " << scene.link(s).name);
        }
      }
      const Eigen::Vector3d tool = X[hand] * kToolPoint_H;
      if (which == &problem.start) {
        BOOST_TEST(tool.x() < 0.45, label << ": the tool is not in front of the scene");
      } else if (problem.scene == "shelf") {
        // Inside the middle-row compartment on the +y side: x 0.60 .. 0.93, y 0.01 .. 0.43,
        // z 0.42 .. 0.80.
        BOOST_TEST((tool.x() > 0.62 && tool.x() < 0.93 && tool.y() > 0.01 && tool.y() < 0.43 && tool.z() > 0.42 &&
                    tool.z() < 0.80),
                   label << ": tool at " << tool.transpose());
      } else if (problem.scene == "narrow_passage") {
        // Through the window: beyond the wall (x > 0.54), within the window's y and z.
        BOOST_TEST((tool.x() > 0.54 && std::abs(tool.y()) < 0.16 && tool.z() > 0.5 && tool.z() < 0.8),
                   label << ": tool at " << tool.transpose());
      } else {
        // Above the table top, between the objects.
        BOOST_TEST(
            (tool.x() > 0.45 && tool.x() < 1.05 && std::abs(tool.y()) < 0.45 && tool.z() > 0.40 && tool.z() < 0.60),
            label << ": tool at " << tool.transpose());
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
