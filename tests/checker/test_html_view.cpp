// World::linkPieces / worldPieces (the pieces the queries use, for display) and the HTML view of a
// world (html_view.h): frames, densifying, the closest pair per frame, the body-level answer where
// it overlaps, and errors with no file written. The page in a real browser is tested by
// tests/viewer/.

#include "checker_test_util.h"

#include "common/body_cases.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/viewer/html_view.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::viewer;
using checker::test::armRobot;
using checker::test::sliderRobot;
using checker::test::testWorldOptions;

namespace {

Eigen::VectorXd slide(double x) { return Eigen::VectorXd::Constant(1, x); }

/// The slider (a 1 m cube on a prismatic x joint) and a 1 m box obstacle centred at x = 3.
World sliderWorld() {
  World world(sliderRobot(1.0), testWorldOptions());
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(3.0, 0.0, 0.0);
  world.addObstacle(Obstacle::box("wall", Eigen::Vector3d::Ones(), X));
  return world;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_html_view)

BOOST_AUTO_TEST_CASE(link_and_world_pieces_are_the_pieces_the_queries_count) {
  World world(armRobot(), testWorldOptions());
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(1.0, 0.0, 0.3);
  world.addObstacle(Obstacle::sphere("ball", 0.1, X));
  int robotPieces = 0;
  for (int l = 0; l < world.robot().numLinks(); ++l) robotPieces += static_cast<int>(world.linkPieces(l).size());
  BOOST_TEST(robotPieces == world.summaryCounts().robotPieces);
  BOOST_TEST(world.linkPieces(world.robot().linkIndex("elbow")).empty());
  const std::vector<World::WorldPieceRef> pieces = world.worldPieces();
  BOOST_TEST_REQUIRE(pieces.size() == 1u);
  BOOST_TEST((pieces[0].body.kind == BodyRef::Kind::Obstacle));
  BOOST_TEST(pieces[0].piece.radius == 0.1);
  BOOST_TEST((pieces[0].piece.X_LP.translation() - X.translation()).norm() < 1e-12);  // posed in the world
  BOOST_CHECK_THROW(world.linkPieces(world.robot().numLinks()), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(frames_carry_the_poses_and_the_closest_pair_of_each_configuration) {
  const World world = sliderWorld();
  WorldViewOptions options;
  options.maxStep = 0.0;
  const ViewScene scene = viewOfWorld(world, {slide(0.0), slide(1.5)}, options);
  BOOST_TEST_REQUIRE(scene.frames.size() == 2u);
  BOOST_TEST(scene.numTracks == 1);               // the cube; base has no geometry
  BOOST_TEST_REQUIRE(scene.bodies.size() == 2u);  // the cube and the obstacle
  BOOST_TEST(scene.bodies[1].name == "obstacle/wall");
  BOOST_TEST(scene.bodies[1].track == -1);
  // Cube [x - 0.5, x + 0.5] against the wall [2.5, 3.5]: distance 2 - x.
  BOOST_TEST(std::abs(scene.frames[0].value - 2.0) < 1e-9);
  BOOST_TEST(std::abs(scene.frames[1].value - 0.5) < 1e-9);
  BOOST_TEST(std::abs(scene.frames[1].poses[0].translation().x() - 1.5) < 1e-12);
  BOOST_TEST(scene.frames[1].contact.nameB == "obstacle/wall");
  BOOST_TEST((scene.frames[1].contact.normal - Eigen::Vector3d::UnitX()).norm() < 1e-9);
}

BOOST_AUTO_TEST_CASE(paths_are_densified_by_max_step_within_max_frames) {
  const World world = sliderWorld();
  WorldViewOptions options;
  options.maxStep = 0.1;
  const ViewScene scene = viewOfWorld(world, {slide(0.0), slide(1.0), slide(1.05)}, options);
  // 10 steps, then 1: 12 frames, waypoints at 0, 10 and 11.
  BOOST_TEST_REQUIRE(scene.frames.size() == 12u);
  for (std::size_t f = 0; f < scene.frames.size(); ++f) {
    BOOST_TEST(scene.frames[f].waypoint == (f == 0 || f == 10 || f == 11), "frame " << f);
  }
  BOOST_TEST(std::abs(scene.frames[5].poses[0].translation().x() - 0.5) < 1e-12);
  options.maxFrames = 6;
  BOOST_TEST(viewOfWorld(world, {slide(0.0), slide(1.0), slide(1.05)}, options).frames.size() <= 6u);
}

// The slab of two touching boxes (tests/common/body_cases.h): the tool 0.04 deep at the seam. The
// closest pair is 0.035 deep, sideways; the slab as one body is 0.04 deep, straight up. Apart, a
// frame has no body answer.
BOOST_AUTO_TEST_CASE(overlapping_frames_carry_the_body_depth_of_the_closest_pairs_bodies) {
  World world(deepcheck::test::gantryRobot(deepcheck::test::toolBox()), testWorldOptions());
  world.addScene(deepcheck::test::sceneOf("slab", deepcheck::test::slabCollisions()), Eigen::Isometry3d::Identity());
  WorldViewOptions options;
  options.maxStep = 0.0;
  const ViewScene scene =
      viewOfWorld(world, {deepcheck::test::gantryQ(0.005, 0, 0.01), deepcheck::test::gantryQ(0.3, 0.1, 0.08)}, options);
  BOOST_TEST_REQUIRE(scene.frames.size() == 2u);
  const ViewFrame& in = scene.frames[0];
  BOOST_TEST_REQUIRE(in.hasContact);
  BOOST_TEST(in.contact.distance == -0.035, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::abs(in.contact.normal.z()) < 1e-9);
  BOOST_TEST_REQUIRE(in.hasBodyContact);
  const ViewContact& body = in.bodyContact;
  BOOST_TEST(body.distance == -0.04, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((body.normal - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9, "normal " << body.normal.transpose());
  BOOST_TEST((body.pointB - body.pointA - body.distance * body.normal).norm() < 1e-9);
  BOOST_TEST(body.nameA == "tool");
  BOOST_TEST(body.nameB == "scene/slab");
  BOOST_TEST(scene.frames[1].hasContact);
  BOOST_TEST(!scene.frames[1].hasBodyContact);

  // The page carries it per frame, beside the pair's contact.
  std::ostringstream page;
  writeHtmlView(scene, page);
  BOOST_TEST(page.str().find("\"bodyContact\":{\"has\":\"10\"") != std::string::npos);
}

// An attached object as the closest pair's A is measured as the object's body, not its link's.
BOOST_AUTO_TEST_CASE(an_attached_objects_body_depth_is_the_objects) {
  World world(deepcheck::test::gantryRobot(deepcheck::test::toolBox()), testWorldOptions());
  world.addScene(deepcheck::test::sceneOf("slab", deepcheck::test::slabCollisions()), Eigen::Isometry3d::Identity());
  // A plate 0.2 x 0.1 x 0.02 hanging 0.1 below the tool frame, its bottom 0.11 below it.
  Eigen::Isometry3d X_TO = Eigen::Isometry3d::Identity();
  X_TO.translation() = Eigen::Vector3d(0, 0, -0.1);
  AttachOptions attach;
  attach.worldFrame = false;
  world.attach("tool", Obstacle::box("plate", Eigen::Vector3d(0.2, 0.1, 0.02), X_TO), attach);
  WorldViewOptions options;
  // The tool frame at z = 0.1: the plate's bottom 0.01 into the slab across the seam, the tool clear.
  const ViewScene scene = viewOfWorld(world, {deepcheck::test::gantryQ(0.0, 0, 0.1)}, options);
  const ViewFrame& f = scene.frames[0];
  BOOST_TEST_REQUIRE(f.hasBodyContact);
  BOOST_TEST(f.contact.nameA == "attached/plate");
  BOOST_TEST(f.bodyContact.nameA == "attached/plate");
  BOOST_TEST(f.bodyContact.distance == -0.01, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((f.bodyContact.normal - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9);
}

BOOST_AUTO_TEST_CASE(bad_configurations_and_scenes_are_named_and_nothing_is_written) {
  const World world = sliderWorld();
  const std::string file = (std::filesystem::temp_directory_path() / "deepcheck_test_html_view.html").string();
  std::filesystem::remove(file);
  const auto throwsNaming = [&](const auto& call, const std::string& text) {
    try {
      call();
      BOOST_ERROR("no error, expected one naming " << text);
    } catch (const std::invalid_argument& e) {
      BOOST_TEST(std::string(e.what()).find(text) != std::string::npos, e.what());
    }
    BOOST_TEST(!std::filesystem::exists(file));
  };
  const Eigen::VectorXd nan = slide(std::numeric_limits<double>::quiet_NaN());
  throwsNaming([&] { writeHtmlView(world, {slide(0.0), nan}, file); }, "configuration 1");
  throwsNaming([&] { writeHtmlView(world, {Eigen::VectorXd::Zero(2)}, file); }, "configuration 0");
  throwsNaming([&] { writeHtmlView(world, {}, file); }, "no configuration");
  WorldViewOptions hide;
  hide.hiddenLinks = {"gripper"};
  throwsNaming([&] { writeHtmlView(world, {slide(0.0)}, file, hide); }, "no link 'gripper'");
  ViewScene scene = viewOfWorld(world, {slide(0.0)});
  scene.bodies[0].track = 3;
  throwsNaming([&] { writeHtmlView(scene, file); }, "follows track 3 of 1");
  scene = viewOfWorld(world, {slide(0.0)});
  scene.frames[0].poses[0].translation().x() = std::numeric_limits<double>::infinity();
  throwsNaming([&] { writeHtmlView(scene, file); }, "frame 0 track 0 is not finite");
  scene.frames.clear();
  throwsNaming([&] { writeHtmlView(scene, file); }, "no frame");
}

BOOST_AUTO_TEST_CASE(page_embeds_the_viewer_and_escapes_names) {
  World world(sliderRobot(1.0), testWorldOptions());
  world.addObstacle(Obstacle::box("</script><b>", Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity()));
  WorldViewOptions options;
  options.title = "a \"title\"";
  std::ostringstream page;
  writeHtmlView(viewOfWorld(world, {slide(-1.5)}, options), page);
  const std::string html = page.str();
  BOOST_TEST(html.find("obstacle/\\u003c/script\\u003e\\u003cb\\u003e") != std::string::npos);
  BOOST_TEST(html.find("</script><b>") == std::string::npos);
  BOOST_TEST(html.find("\"title\":\"a \\\"title\\\"\"") != std::string::npos);
  BOOST_TEST(html.find("THREE.OrbitControls") != std::string::npos);
  BOOST_TEST(html.find("@DEEPCHECK_") == std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
