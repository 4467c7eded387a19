#pragma once
// A self-contained HTML page showing what deepcheck computed, for a browser (three.js inlined,
// nothing fetched when the page is viewed: it works offline, opened by double-click).
//
// The page shows
//   - bodies: each with its original geometry shaded (URDF boxes, spheres, cylinders, meshes) and
//     its convex pieces as translucent wireframes, toggled per layer and per body;
//   - frames: one or more poses of the moving bodies (a configuration, a path densified for
//     animation, the queries of a case file), with a slider and a play button;
//   - per frame, the closest pair: witness points, normal, and an arrow coloured by sign: green from
//     A's witness to B's (distance > 0), red for a penetration, depth x normal from B's witness to
//     A's (the translation of B that separates the pair);
//   - per frame, where the closest pair overlaps, the body-level push-out: the penetration depth of
//     the pair's two whole bodies (each the union of its pieces, World::bodySignedDistance) as its
//     own arrow, depth x normal from B's witness, in its own layer ("body depth");
//   - per frame, a value (the minimum signed distance) plotted under the view, waypoints marked,
//     the smallest value marked as the worst frame.
// The data is JSON inside the page; the page's JavaScript and CSS live in viewer/ and are embedded
// when the library (deepcheck::viewer) is built. The URL hash selects the frame shown first: #t=0, #t=end or #t=N.
//
// Frames: bodies are posed in the world W (z up); a moving body follows a track, one pose per
// frame. Units: metres.
//
// Errors: std::invalid_argument naming the bad value (a track index, a non-finite pose or point,
// a configuration of the wrong size or with a NaN, naming the configuration and the variable) or
// the file that cannot be written; nothing is written then.

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/mesh.h"
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace deepcheck::viewer {

/// An original geometry of a body (shaded in the page).
struct ViewShape {
  /// Box (boxSize), Sphere (radius), Cylinder (radius, length along z) or Mesh (`mesh` below).
  robots::Geometry geometry;
  std::shared_ptr<const robots::TriangleMesh> mesh;        ///< Mesh: vertices in G, metres
  Eigen::Isometry3d X_BG = Eigen::Isometry3d::Identity();  ///< pose of G in the body frame B
};

/// Something drawn: a robot link, a scene link, an obstacle, a shape of a case file, a mesh.
struct ViewBody {
  std::string name;   ///< shown in the per-body list
  std::string layer;  ///< group toggled together, e.g. "robot", "scene", "obstacle"
  std::vector<ViewShape> shapes;
  std::vector<robots::CollisionPiece> pieces;  ///< X_LP: pose of the piece in the body frame
  /// -1: fixed at X_WB; otherwise the index of the track (ViewFrame::poses) it follows.
  int track = -1;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  bool visible = true;  ///< shown when the page opens
};

/// The closest pair of a frame (the conventions of world.h: normal from A towards B,
/// pointB - pointA = distance * normal).
struct ViewContact {
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::string nameA;
  std::string nameB;
};

struct ViewFrame {
  std::vector<Eigen::Isometry3d> poses;  ///< X_WB of every track
  std::vector<bool> hidden;              ///< per track, true to hide it in this frame (empty: none)
  bool waypoint = true;                  ///< false for frames interpolated between waypoints
  bool hasContact = false;
  ViewContact contact;
  /// The body-level answer for the contact's two bodies (World::bodySignedDistance), set where the
  /// closest pair overlaps: its depth can exceed the pair's and its normal differ.
  bool hasBodyContact = false;
  ViewContact bodyContact;
  /// Plotted under the view (NaN: no value for this frame).
  double value = std::numeric_limits<double>::quiet_NaN();
  std::string label;  ///< shown with the frame number (e.g. "waypoint 3", "query on line 12")
};

struct ViewScene {
  std::string title;
  std::string caption;  ///< shown over the view; may have several lines
  std::string valueName = "min signed distance (m)";
  int numTracks = 0;
  std::vector<ViewBody> bodies;
  std::vector<ViewFrame> frames;  ///< at least one
};

/// Writes the page of `scene` to `out`. Throws std::invalid_argument (see the header comment).
void writeHtmlView(const ViewScene& scene, std::ostream& out);
/// Same, to `file`: the page is built in memory first, so on an error no file is written.
void writeHtmlView(const ViewScene& scene, const std::string& file);

struct WorldViewOptions {
  std::string title = "deepcheck";
  std::string caption;
  /// Frames are added between consecutive configurations so that no variable moves more than
  /// this between frames (rad or m, straight lines in configuration space as the planners
  /// interpolate); 0 or infinity shows the configurations only.
  double maxStep = 0.05;
  /// At most this many frames in all: maxStep is enlarged when the path is long.
  int maxFrames = 2000;
  /// Robot links to hide when the page opens (their names; an unknown name is an error).
  std::vector<std::string> hiddenLinks;
};

/// The page of `world` along `configurations` (one: a single pose; several: a path): the robot's
/// links follow the frames, scenes and obstacles stay fixed, every frame carries the world's
/// closest pair (World::signedDistance) and, where that pair overlaps, the body-level signed
/// distance of its link (or attached object) and the body it overlaps (World::bodySignedDistance
/// with default options): the deepest pair names the body the link overlaps most deeply.
ViewScene viewOfWorld(const checker::World& world, const std::vector<Eigen::VectorXd>& configurations,
                      const WorldViewOptions& options = WorldViewOptions());

/// writeHtmlView(viewOfWorld(world, configurations, options), file).
void writeHtmlView(const checker::World& world, const std::vector<Eigen::VectorXd>& configurations,
                   const std::string& file, const WorldViewOptions& options = WorldViewOptions());

/// The bodies of a URDF model's links at the poses X_WL: shapes from their collision elements
/// (meshes loaded once per file and scale) and the given pieces (`pieces[link]`, link frame).
/// Links without geometry are skipped; each body's track is -1 (set it to animate).
std::vector<ViewBody> linkBodies(const robots::RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL,
                                 const std::vector<std::vector<robots::CollisionPiece>>& pieces,
                                 const std::string& layer, const std::string& namePrefix);

}  // namespace deepcheck::viewer
