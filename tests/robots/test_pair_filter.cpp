// Collision-pair filtering and SRDF files: adjacency through links without geometry, the
// Default / Always / Never reasons on a robot built so that every answer is known, SRDF round
// trips and bad input, and the real robots of ../shared against the SRDFs shipped with them.

#include "robots_test_util.h"

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::sharedDir;
using deepcheck::robots::test::TempDir;

namespace {

/// Random configurations of the fresh, independent sample the 'Never' pairs are checked
/// against; a different seed and generator than the filter's.
constexpr int kFreshSamples = 3000;
constexpr unsigned kFreshSeed = 20240613;

using PairSet = std::set<std::pair<std::string, std::string>>;

/// A robot whose every pair has a known answer (frames: world = base, metres):
///   base   box 0.2 at the origin
///   arm    turns about z (joint j1, [-pi, pi]) at height 0.3; a 1.0 x 0.1 x 0.1 bar from
///          x = 0.1 to 1.1 of its frame
///   spacer fixed to arm, NO geometry
///   tip    fixed to spacer; a box 0.1 at x = 1.2: adjacent to arm through spacer
///   ghost  fixed to tip; a box 0.1 at x = 0.3 inside the bar: overlaps arm in every
///          configuration, but is not adjacent to it (tip, with geometry, is between them)
///   post   fixed to base; a box 0.1 at (0.6, 0, 0.3): the bar sweeps through it around q = 0
///   far    fixed to post; a box 0.1 at z = 2: never near anything
const char* kToyUrdf = R"(<?xml version="1.0"?>
<robot name="toy">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="0.6 0 0"/><geometry><box size="1.0 0.1 0.1"/></geometry></collision></link>
  <link name="spacer"/>
  <link name="tip"><collision><origin xyz="1.2 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="ghost"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="post"><collision><origin xyz="0.6 0 0.3"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="far"><collision><origin xyz="0 0 2"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
  <joint name="spacer_joint" type="fixed"><parent link="arm"/><child link="spacer"/></joint>
  <joint name="tip_joint" type="fixed"><parent link="spacer"/><child link="tip"/></joint>
  <joint name="ghost_joint" type="fixed"><parent link="tip"/><child link="ghost"/></joint>
  <joint name="post_joint" type="fixed"><parent link="base"/><child link="post"/></joint>
  <joint name="far_joint" type="fixed"><parent link="post"/><child link="far"/></joint>
</robot>
)";

RobotModel loadToy() { return RobotModel::fromUrdfString(kToyUrdf, "", {}, "toy.urdf"); }

std::map<std::pair<std::string, std::string>, DisableReason> byKey(const std::vector<DisabledPair>& pairs) {
  std::map<std::pair<std::string, std::string>, DisableReason> m;
  for (const DisabledPair& p : pairs) m[pairKey(p.link1, p.link2)] = p.reason;
  return m;
}

PairSet keys(const std::vector<DisabledPair>& pairs, std::optional<DisableReason> only = {}) {
  PairSet s;
  for (const DisabledPair& p : pairs) {
    if (!only || p.reason == *only) s.insert(pairKey(p.link1, p.link2));
  }
  return s;
}

std::string join(const PairSet& s) {
  std::string out;
  for (const auto& [a, b] : s) out += "\n    " + a + " - " + b;
  return out.empty() ? " (none)" : out;
}

/// Pairs of links that collide in at least one of `count` configurations drawn uniformly in the
/// joint limits with std::mt19937(seed) (independent of the filter's generator).
PairSet collidingInFreshSample(const RobotModel& model, const std::vector<std::vector<CollisionPiece>>& pieces,
                               int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::uniform_real_distribution<double>> dist;
  for (int v = 0; v < model.numVariables(); ++v) {
    dist.emplace_back(model.lowerLimits()[v], model.upperLimits()[v]);
  }
  PairSet colliding;
  Eigen::VectorXd q(model.numVariables());
  std::vector<Eigen::Isometry3d> X_WL;
  for (int s = 0; s < count; ++s) {
    for (int v = 0; v < q.size(); ++v) q[v] = dist[v](rng);
    forwardKinematics(model, q, X_WL);
    for (const auto& [i, j] : collidingLinkPairs(model, pieces, X_WL)) {
      colliding.insert(pairKey(model.link(i).name, model.link(j).name));
    }
  }
  return colliding;
}

/// Against a shipped SRDF, the properties that must hold whatever the meshes:
/// their 'Adjacent' pairs are ours too, and no pair we call 'Never' collides in a fresh sample.
void checkAgainstShipped(const RobotModel& model, const std::string& srdfPath) {
  const auto pieces = collisionPieces(model);
  const PairFilterResult ours = computeDisabledPairs(model, pieces);  // 10,000 samples, seed 1
  const std::vector<DisabledPair> theirs = readSrdfDisabledPairs(srdfPath);
  BOOST_REQUIRE(!theirs.empty());
  checkDisabledPairs(model, theirs, srdfPath);

  const auto ourReasons = byKey(ours.disabled);

  // Adjacency is structural: their Adjacent pairs are ours.
  for (const auto& k : keys(theirs, DisableReason::Adjacent)) {
    const auto o = ourReasons.find(k);
    BOOST_CHECK_MESSAGE(o != ourReasons.end() && o->second == DisableReason::Adjacent,
                        k.first << " - " << k.second << " is Adjacent in " << srdfPath << " but not for us");
  }

  // 'Never' holds up in a fresh sample drawn with another generator and seed.
  const PairSet fresh = collidingInFreshSample(model, pieces, kFreshSamples, kFreshSeed);
  const PairSet never = keys(ours.disabled, DisableReason::Never);
  PairSet wrong;
  std::set_intersection(never.begin(), never.end(), fresh.begin(), fresh.end(), std::inserter(wrong, wrong.end()));
  BOOST_CHECK_MESSAGE(wrong.empty(), "pairs we call Never collide in the fresh sample:" << join(wrong));
  // The fresh sample is meaningful: it does find collisions among the pairs we keep checking.
  PairSet enabledColliding;
  for (const LinkPairReport& r : ours.pairs) {
    const auto k = pairKey(model.link(r.link1).name, model.link(r.link2).name);
    if (!r.reason && fresh.count(k)) enabledColliding.insert(k);
  }
  BOOST_CHECK_MESSAGE(!enabledColliding.empty(), "the fresh sample found no collision at all");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_pair_filter)

BOOST_AUTO_TEST_CASE(reason_words) {
  for (int r = 0; r < kNumDisableReasons; ++r) {
    const auto reason = static_cast<DisableReason>(r);
    BOOST_TEST((parseDisableReason(toString(reason)) == reason));
  }
  // MoveIt writes the words capitalized and accepts any other text.
  BOOST_TEST((parseDisableReason("never") == DisableReason::Other));
  BOOST_TEST((parseDisableReason("Common") == DisableReason::Other));
  BOOST_TEST((parseDisableReason("") == DisableReason::Unspecified));
  BOOST_TEST((pairKey("b", "a") == pairKey("a", "b")));
}

BOOST_AUTO_TEST_CASE(round_trip) {
  const std::vector<DisabledPair> pairs = {
      {"base_link", "link1", DisableReason::Adjacent},
      {"finger_l", "finger_r", DisableReason::Default},
      {"a", "b", DisableReason::Always},
      {"link2", "link7", DisableReason::Never},
      {"tool", "camera", DisableReason::User},
      {"x", "y", DisableReason::Unspecified},
      {"odd<&>\"'name", "other", DisableReason::Never},
      {"gripper", "camera", DisableReason::Other, "Common & <shared>"},
  };
  const std::string text = srdfText("robot & co", pairs, "a comment -- with dashes");
  const std::vector<DisabledPair> back = parseSrdfDisabledPairs(text, "memory");
  BOOST_REQUIRE_EQUAL(back.size(), pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    BOOST_TEST(back[k].link1 == pairs[k].link1);
    BOOST_TEST(back[k].link2 == pairs[k].link2);
    BOOST_TEST((back[k].reason == pairs[k].reason));
    BOOST_TEST(back[k].reasonText == pairs[k].reasonText);
  }
  // Through a file, and again: writing what was read gives the same text.
  TempDir dir;
  const std::string path = (dir.path() / "robot.srdf").string();
  writeSrdf(path, "robot & co", pairs, "a comment -- with dashes");
  const std::vector<DisabledPair> fromFile = readSrdfDisabledPairs(path);
  BOOST_TEST(srdfText("robot & co", fromFile, "a comment -- with dashes") == text);
}

BOOST_AUTO_TEST_CASE(round_trip_of_computed_pairs) {
  const RobotModel toy = loadToy();
  const PairFilterResult r = computeDisabledPairs(toy, collisionPieces(toy));
  TempDir dir;
  const std::string path = (dir.path() / "toy.srdf").string();
  writeSrdf(path, toy.name(), r.disabled);
  const std::vector<DisabledPair> back = readSrdfDisabledPairs(path);
  checkDisabledPairs(toy, back, path);
  BOOST_TEST((byKey(back) == byKey(r.disabled)));
}

BOOST_AUTO_TEST_CASE(reads_moveit_extras) {
  // Everything but <disable_collisions> is ignored; a missing reason is Unspecified.
  const std::string xml = R"(<?xml version="1.0"?>
<robot name="r">
  <group name="arm"><chain base_link="a" tip_link="c"/></group>
  <disable_collisions link1="a" link2="b" reason="Adjacent"/>
  <virtual_joint name="v" type="fixed" parent_frame="world" child_link="a"/>
  <disable_collisions link1="b" link2="c"/>
</robot>)";
  const auto pairs = parseSrdfDisabledPairs(xml, "extras.srdf");
  BOOST_REQUIRE_EQUAL(pairs.size(), 2u);
  BOOST_TEST((pairs[0].reason == DisableReason::Adjacent));
  BOOST_TEST((pairs[1].reason == DisableReason::Unspecified));
  BOOST_TEST(pairs[1].link2 == "c");
}

BOOST_AUTO_TEST_CASE(any_reason_text) {
  // MoveIt accepts any reason: unknown text is Other and kept as written; none is Unspecified.
  const std::string xml = R"(<robot name="r">
  <disable_collisions link1="a" link2="b" reason="Common"/>
  <disable_collisions link1="b" link2="c"/>
  <disable_collisions link1="c" link2="d" reason="User"/>
</robot>)";
  const auto pairs = parseSrdfDisabledPairs(xml, "common.srdf");
  BOOST_REQUIRE_EQUAL(pairs.size(), 3u);
  BOOST_TEST((pairs[0].reason == DisableReason::Other));
  BOOST_TEST(pairs[0].reasonText == "Common");
  BOOST_TEST(reasonText(pairs[0]) == "Common");
  BOOST_TEST((pairs[1].reason == DisableReason::Unspecified));
  BOOST_TEST(reasonText(pairs[1]) == "");
  BOOST_TEST((pairs[2].reason == DisableReason::User));
  BOOST_TEST(pairs[2].reasonText.empty());
  const std::string written = srdfText("r", pairs);
  BOOST_TEST(written.find("link2=\"b\" reason=\"Common\"/>") != std::string::npos);
  BOOST_TEST(written.find("link2=\"c\"/>") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(bad_srdf) {
  checkThrows([] { parseSrdfDisabledPairs("<robot><disable_collisions", "broken.srdf"); },
              {"broken.srdf", "malformed XML", "line"});
  checkThrows([] { parseSrdfDisabledPairs("<?xml version=\"1.0\"?><model/>", "m.srdf"); }, {"m.srdf", "root element"});
  checkThrows(
      [] { parseSrdfDisabledPairs("<robot name=\"r\">\n<disable_collisions link1=\"a\"/>\n</robot>", "half.srdf"); },
      {"half.srdf", "line 2", "link2"});
  checkThrows([] { readSrdfDisabledPairs("/nonexistent/dir/robot.srdf"); },
              {"/nonexistent/dir/robot.srdf", "cannot open"});
  const RobotModel toy = loadToy();
  checkThrows(
      [&] {
        checkDisabledPairs(toy, {{"arm", "elbow", DisableReason::Never}}, "t.srdf");
      },
      {"t.srdf", "'elbow'", "'toy'"});
  checkThrows(
      [&] {
        checkDisabledPairs(toy, {{"arm", "arm", DisableReason::Never}}, "t.srdf");
      },
      {"t.srdf", "'arm'", "same link"});
  checkThrows([&] { enabledLinkPairs(toy, collisionPieces(toy), {{"arm", "nope", DisableReason::User}}); }, {"'nope'"});
}

BOOST_AUTO_TEST_CASE(bad_options) {
  const RobotModel toy = loadToy();
  const auto pieces = collisionPieces(toy);
  PairFilterOptions o;
  o.samples = -1;
  checkThrows([&] { computeDisabledPairs(toy, pieces, o); }, {"'toy'", "-1"});
  o = {};
  o.alwaysFraction = 0.0;
  checkThrows([&] { computeDisabledPairs(toy, pieces, o); }, {"'toy'", "alwaysFraction"});
  o = {};
  o.defaultConfiguration = Eigen::VectorXd::Zero(3);
  checkThrows([&] { computeDisabledPairs(toy, pieces, o); }, {"default configuration", "'toy'", "3 values"});
  o = {};
  o.defaultConfiguration = Eigen::VectorXd::Constant(1, std::numeric_limits<double>::quiet_NaN());
  checkThrows([&] { computeDisabledPairs(toy, pieces, o); }, {"default configuration", "j1", "nan"});
  checkThrows([&] { computeDisabledPairs(toy, {}, {}); }, {"'toy'", "pieces for 0 links"});
}

BOOST_AUTO_TEST_CASE(adjacency_through_links_without_geometry) {
  const RobotModel toy = loadToy();
  const auto pieces = collisionPieces(toy);
  PairSet adjacent;
  for (const auto& [i, j] : adjacentLinkPairs(toy, pieces)) {
    BOOST_TEST(i < j);
    adjacent.insert(pairKey(toy.link(i).name, toy.link(j).name));
  }
  const PairSet expected = {pairKey("base", "arm"), pairKey("base", "post"), pairKey("post", "far"),
                            pairKey("arm", "tip"), pairKey("tip", "ghost")};
  BOOST_TEST((adjacent == expected), "adjacent:" << join(adjacent));

  // A link without geometry with several children: all of them and its parent are adjacent.
  const std::string hub = R"(<robot name="hub">
  <link name="p"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="h"/>
  <link name="h2"/>
  <link name="c1"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="c2"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="c3"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="g"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="a" type="fixed"><parent link="p"/><child link="h"/></joint>
  <joint name="b" type="fixed"><parent link="h"/><child link="c1"/></joint>
  <joint name="c" type="fixed"><parent link="h"/><child link="h2"/></joint>
  <joint name="d" type="fixed"><parent link="h2"/><child link="c2"/></joint>
  <joint name="e" type="fixed"><parent link="h2"/><child link="c3"/></joint>
  <joint name="f" type="fixed"><parent link="c3"/><child link="g"/></joint>
</robot>)";
  const RobotModel model = RobotModel::fromUrdfString(hub, "", {}, "hub.urdf");
  PairSet got;
  for (const auto& [i, j] : adjacentLinkPairs(model, collisionPieces(model))) {
    got.insert(pairKey(model.link(i).name, model.link(j).name));
  }
  const PairSet want = {pairKey("p", "c1"),  pairKey("p", "c2"),  pairKey("p", "c3"), pairKey("c1", "c2"),
                        pairKey("c1", "c3"), pairKey("c2", "c3"), pairKey("c3", "g")};
  BOOST_TEST((got == want), "adjacent:" << join(got));
}

BOOST_AUTO_TEST_CASE(reasons_on_a_known_robot) {
  const RobotModel toy = loadToy();
  const auto pieces = collisionPieces(toy);
  PairFilterOptions o;
  o.samples = 4000;
  o.seed = 7;
  const PairFilterResult r = computeDisabledPairs(toy, pieces, o);
  BOOST_TEST(r.numGeometryLinks == 6);
  BOOST_TEST(r.numPairs() == 15);
  BOOST_TEST(r.samples == 4000);
  using R = DisableReason;
  const std::map<std::pair<std::string, std::string>, DisableReason> expected = {
      {pairKey("base", "arm"), R::Adjacent},  {pairKey("base", "post"), R::Adjacent},
      {pairKey("post", "far"), R::Adjacent},  {pairKey("arm", "tip"), R::Adjacent},
      {pairKey("tip", "ghost"), R::Adjacent}, {pairKey("arm", "post"), R::Default},
      {pairKey("arm", "ghost"), R::Default},  {pairKey("base", "far"), R::Never},
      {pairKey("base", "tip"), R::Never},     {pairKey("base", "ghost"), R::Never},
      {pairKey("arm", "far"), R::Never},      {pairKey("post", "tip"), R::Never},
      {pairKey("post", "ghost"), R::Never},   {pairKey("far", "tip"), R::Never},
      {pairKey("far", "ghost"), R::Never}};
  const auto got = byKey(r.disabled);
  BOOST_TEST(got.size() == expected.size());
  for (const auto& [k, reason] : expected) {
    const auto it = got.find(k);
    BOOST_CHECK_MESSAGE(it != got.end() && it->second == reason,
                        k.first << " - " << k.second << ": expected " << toString(reason) << ", got "
                                << (it == got.end() ? "checked" : toString(it->second)));
  }
  BOOST_TEST(r.numEnabled() == 0);
  BOOST_TEST(r.count(R::Adjacent) == 5);
  BOOST_TEST(enabledLinkPairs(toy, pieces, r.disabled).empty());

  // Without the Default test: the bar sweeps through the post in part of the turn (about 6 %
  // of it: the pair stays to be checked), and the ghost is inside the bar in every sample.
  o.checkDefault = false;
  const PairFilterResult s = computeDisabledPairs(toy, pieces, o);
  const auto got2 = byKey(s.disabled);
  BOOST_TEST(got2.count(pairKey("arm", "post")) == 0u);
  BOOST_TEST((got2.at(pairKey("arm", "ghost")) == R::Always));
  BOOST_TEST(s.numEnabled() == 1);
  for (const LinkPairReport& p : s.pairs) {
    const auto k = pairKey(toy.link(p.link1).name, toy.link(p.link2).name);
    if (k == pairKey("arm", "post")) {
      BOOST_TEST(!p.reason.has_value());
      BOOST_TEST(p.collisions > 0.02 * o.samples);
      BOOST_TEST(p.collisions < 0.12 * o.samples);
    }
    if (k == pairKey("arm", "ghost")) BOOST_TEST(p.collisions == o.samples);
  }
  const auto enabled = enabledLinkPairs(toy, pieces, s.disabled);
  BOOST_REQUIRE_EQUAL(enabled.size(), 1u);
  BOOST_TEST((pairKey(toy.link(enabled[0].first).name, toy.link(enabled[0].second).name) == pairKey("arm", "post")));

  // No samples: nothing is Never or Always.
  o.samples = 0;
  const PairFilterResult t = computeDisabledPairs(toy, pieces, o);
  BOOST_TEST(t.count(R::Never) == 0);
  BOOST_TEST(t.count(R::Always) == 0);
  BOOST_TEST(t.numEnabled() == 10);
}

BOOST_AUTO_TEST_CASE(seeded_and_prefix_consistent) {
  const RobotModel toy = loadToy();
  const auto pieces = collisionPieces(toy);
  PairFilterOptions o;
  o.checkDefault = false;
  o.samples = 500;
  o.seed = 99;
  const PairFilterResult a = computeDisabledPairs(toy, pieces, o);
  const PairFilterResult b = computeDisabledPairs(toy, pieces, o);
  BOOST_TEST(srdfText("toy", a.disabled) == srdfText("toy", b.disabled));
  for (std::size_t k = 0; k < a.pairs.size(); ++k) BOOST_TEST(a.pairs[k].collisions == b.pairs[k].collisions);
  // A longer run with the same seed starts with the same configurations: every count grows.
  o.samples = 2000;
  const PairFilterResult c = computeDisabledPairs(toy, pieces, o);
  for (std::size_t k = 0; k < a.pairs.size(); ++k) BOOST_TEST(c.pairs[k].collisions >= a.pairs[k].collisions);
}

BOOST_AUTO_TEST_CASE(default_configuration_like_moveit) {
  const std::string urdf = R"(<robot name="d">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="inside" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="2" effort="1" velocity="1"/></joint>
  <joint name="outside" type="prismatic"><parent link="b"/><child link="c"/><axis xyz="1 0 0"/>
    <limit lower="0.5" upper="1.5" effort="1" velocity="1"/></joint>
</robot>)";
  const RobotModel m = RobotModel::fromUrdfString(urdf, "", {}, "d.urdf");
  const Eigen::VectorXd q = pairFilterDefaultConfiguration(m);
  BOOST_TEST(q[0] == 0.0);  // 0 is within [-1, 2]
  BOOST_TEST(q[1] == 1.0);  // 0 is not within [0.5, 1.5]: the middle
}

BOOST_AUTO_TEST_CASE(panda_against_moveit_srdf) {
  if (!haveShared("panda_against_moveit_srdf")) return;
  LoadOptions o;
  o.packageRoots = {sharedDir() + "/robots/panda"};
  o.useRosPackagePath = false;
  const RobotModel panda =
      RobotModel::fromUrdfFile(sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf", o);
  checkAgainstShipped(panda, sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf");
  // The Panda's adjacency is exactly MoveIt's, panda_link8 (no geometry) included.
  const auto pieces = collisionPieces(panda);
  PairSet ours;
  for (const auto& [i, j] : adjacentLinkPairs(panda, pieces)) {
    ours.insert(pairKey(panda.link(i).name, panda.link(j).name));
  }
  const PairSet theirs =
      keys(readSrdfDisabledPairs(sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf"),
           DisableReason::Adjacent);
  BOOST_TEST((ours == theirs), "ours:" << join(ours) << "\ntheirs:" << join(theirs));
  BOOST_TEST(ours.count(pairKey("panda_link7", "panda_hand")) == 1u);
}

BOOST_AUTO_TEST_CASE(ur5_against_example_robot_data_srdf) {
  if (!haveShared("ur5_against_example_robot_data_srdf")) return;
  LoadOptions o;
  o.packageRoots = {sharedDir() + "/robots/ur5"};
  o.useRosPackagePath = false;
  const RobotModel ur5 = RobotModel::fromUrdfFile(
      sharedDir() + "/robots/ur5/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf", o);
  checkAgainstShipped(ur5, sharedDir() + "/robots/ur5/example-robot-data/robots/ur_description/srdf/ur5.srdf");
}

BOOST_AUTO_TEST_SUITE_END()
