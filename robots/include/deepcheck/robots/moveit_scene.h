#pragma once
// MoveIt planning scenes written as YAML (moveit_msgs/PlanningScene, as MoveIt, Robowflex and
// MotionBenchMaker write them): the collision objects of `world: collision_objects:`, each a set
// of boxes, spheres, cylinders, cones and meshes posed in a named frame.
//
// What is read, per collision object:
//   id                  required, unique in the file, not empty
//   header.frame_id     required: the frame F the object is given in (a robot link, after the
//                       caller's aliases; see shapeWorldPoses)
//   pose                optional: the object's pose X_FO (MoveIt's newer format); identity when
//                       absent. Shapes are posed relative to it: X_FS = X_FO * X_OS.
//   primitives          list of {type, dimensions}; type box, sphere, cylinder or cone (any case,
//                       or the shape_msgs numbers 1 to 4), dimensions as shape_msgs orders them:
//                         box [x, y, z] (full edge lengths), sphere [radius],
//                         cylinder [height, radius], cone [height, radius]
//                       (cylinders and cones along z of the shape's frame, centred on its origin;
//                       the cone's base at z = -height/2, its tip at +height/2).
//   primitive_poses     one pose X_OS per primitive
//   meshes              list of {resource (or filename), scale (or dimensions): [sx, sy, sz]};
//                       resource is package://PKG/path (package_path.h, searched in
//                       SceneLoadOptions::packageRoots then ROS_PACKAGE_PATH), file://path or a
//                       plain path; relative paths are relative to the YAML file's folder. The
//                       file is found here; it is read later (collision_geometry.h, mesh_loader.h).
//                       Or a shape_msgs/Mesh given inline, as MoveIt publishes a mesh object:
//                       {vertices: [{x:, y:, z:}...], triangles: [{vertex_indices: [i, j, k]}...]}
//                       (0-based indices), an in-memory mesh (SceneShape::mesh) like a cone's, at
//                       most SceneLoadOptions::maxInlineMeshElements vertices and triangles in all.
//   mesh_poses          one pose X_OS per mesh
//   operation           optional; only "add" (0, or b'\x00' as `ros2 topic echo` prints the byte)
//                       is accepted: a scene file describes a world
//   type, subframe_names, subframe_poses   accepted and ignored (no geometry)
// A pose is {position: [x, y, z], orientation: [x, y, z, w]} or the message form
// {position: {x:, y:, z:}, orientation: {x:, y:, z:, w:}}. A quaternion whose norm is within
// tol::kSceneQuaternionNorm of 1 is normalised; any other is an error.
// Top level:
//   world                     its `collision_objects`, and its `octomap` (octomap_msgs/
//                             OctomapWithPose, always present in what MoveIt and `ros2 topic
//                             echo` write): accepted when its octomap.data is absent or empty (as
//                             MoveIt, which ignores an octomap without data), an error naming the
//                             line ("an octomap with data is not supported") otherwise.
//   robot_state               its `attached_collision_objects` (PlanningScene::attached): each
//                             {link_name, object (a collision object as above), touch_links};
//                             detach_posture and weight are accepted and ignored. joint_state,
//                             multi_dof_joint_state and is_diff are accepted and ignored: the
//                             configuration is the caller's.
//   allowed_collision_matrix  PlanningScene::allowed: entry_names with entry_values[i].enabled
//                             (one bool per name; as MoveIt, only the upper triangle i < j counts)
//                             and default_entry_names with default_entry_values; only true entries
//                             are kept. Names are not resolved here (the world does): an unknown
//                             name is no error; a name listed twice or lists of mismatched sizes
//                             are.
//   fixed_frame_transforms    entries accepted when their transform is the identity
//                             (MotionBenchMaker's cage says base_link is the planning frame this
//                             way; MoveIt writes the model frame to itself) and rejected otherwise.
//   name                      PlanningScene::name.
//   robot_model_name, link_padding, link_scale, object_colors, is_diff: accepted and ignored.
// An id names one object: world and attached objects share the ids' name space.
// Any other key is an error (a misspelt key must not silently drop an object).
//
// Cones. A cone becomes an in-memory triangle mesh (SceneShape::mesh): the circumscribed
// pyramid whose base is the regular N-gon tangent to the base circle (apothem = radius), N
// chosen as for cylinders (collision_geometry.h: cylinderSides with coneMaxDeviation). It
// CONTAINS the cone and sticks out of it by at most radius * (1 / cos(pi / N) - 1), at the base
// corners. It is convex, so its convex hull (the default MeshDecomposer) is exactly it.
//
// Errors: std::invalid_argument, the message starting with "planning scene '<file>', line <n>"
// (1-based; the line of the offending node, or of its parent when a key is missing), then the
// object ("object 'Can1'", "attached object 'tool'", or "object <index>" before its id is
// known), then what is wrong:
// malformed YAML, a missing key, an unknown key or primitive type, a wrong number of dimensions,
// a size that is not positive, a number that is not finite (.nan, .inf), a quaternion far from
// unit norm, a mesh that cannot be found (every place searched is listed), a number of magnitude
// above geometry::range::kMaxCoordinate (1e50), maps and sequences nested deeper than
// kMaxNestingDepth (robot_model.h), more shapes than SceneLoadOptions::maxShapes.
//
// Frames: F the object's frame (header.frame_id), O the object (pose), S a shape, W the world.

#include "deepcheck/robots/mesh.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"
#include "deepcheck/robots/tolerances.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::robots {

namespace tol {
/// A quaternion read from a scene is normalised when | |q| - 1 | <= kSceneQuaternionNorm
/// (dimensionless) and rejected otherwise. Files written by hand round components to 2 or 3
/// digits ([0.707, 0, 0, 0.707] has norm 0.99985); a 1 % error is such rounding, anything larger
/// is a mistake (a zero quaternion, a missing component, Euler angles).
constexpr double kSceneQuaternionNorm = 1e-2;
}  // namespace tol

/// One shape of a collision object.
struct SceneShape {
  /// Box, Sphere, Cylinder or Mesh (meshUri, meshPath, meshScale) as for a URDF. A cone is
  /// type Mesh with an empty meshPath and its pyramid in `mesh`.
  Geometry geometry;
  /// The in-memory mesh of a cone (see the header comment); null otherwise.
  std::shared_ptr<const TriangleMesh> mesh;
  /// Pose of the shape in the object's frame F (object pose included).
  Eigen::Isometry3d X_FS = Eigen::Isometry3d::Identity();
  /// "primitive 0 (box)", "primitive 2 (cone, 24-sided pyramid)", "mesh 0 (shelf.stl)".
  std::string name;
  int line = 0;  ///< 1-based line of the shape in the file
};

struct SceneObject {
  std::string id;
  std::string frameId;                                     ///< header.frame_id as written
  Eigen::Isometry3d X_FO = Eigen::Isometry3d::Identity();  ///< the object pose (identity if none)
  std::vector<SceneShape> shapes;                          ///< primitives first, then meshes, in file order
  int line = 0;                                            ///< 1-based line where the object starts
};

/// Collisions a scene allows (MoveIt's allowed_collision_matrix): names are robot links or
/// object ids (an attached object's id included).
struct AllowedCollisions {
  /// Pairs allowed to touch, each once, as written (entry_names / entry_values set to true).
  std::vector<std::pair<std::string, std::string>> pairs;
  /// Names allowed to touch anything (default_entry_names whose default_entry_values is true).
  std::vector<std::string> always;
};

/// An object attached to a robot link (robot_state.attached_collision_objects): it moves with
/// the link and is checked against the scene and the robot's other links, but for touchLinks.
struct AttachedObject {
  std::string linkName;  ///< the link it is attached to
  /// The object; its frameId and X_FO place it at the scene's configuration, and it then keeps
  /// its pose relative to linkName.
  SceneObject object;
  std::vector<std::string> touchLinks;  ///< links it may touch (linkName always may)
  int line = 0;                         ///< 1-based line where the attached object starts
};

struct PlanningScene {
  std::string source;                    ///< the file (or the name given to parsePlanningScene)
  std::string name;                      ///< the scene's name (YAML `name`, a .scene file's first line); may be empty
  std::vector<SceneObject> objects;      ///< in file order
  std::vector<AttachedObject> attached;  ///< in file order
  AllowedCollisions allowed;
  /// Index of the object called `id`, -1 when there is none.
  int objectIndex(const std::string& id) const;
};

struct SceneLoadOptions {
  /// Package roots searched first for package:// resources (e.g. --package-path arguments).
  std::vector<std::string> packageRoots;
  /// Also search ROS_PACKAGE_PATH (and AMENT_PREFIX_PATH/share).
  bool useRosPackagePath = true;
  /// Largest distance a cone's pyramid may stick out of the cone, metres (> 0).
  double coneMaxDeviation = tol::kCylinderMaxDeviation;
  /// Most shapes (primitives and meshes, over all objects) a scene may hold, and so most objects;
  /// a list repeated through YAML aliases counts once per repetition. The count is checked before
  /// each list is read, so an alias expansion stops as soon as it passes the limit.
  std::size_t maxShapes = 10000;
  /// Most vertices and triangles of inline meshes (shape_msgs/Mesh) over the whole scene, counted
  /// before each list is read (YAML aliases as expanded).
  std::size_t maxInlineMeshElements = 10000000;
};

/// Reads a planning-scene file: MoveIt's .scene text when isSceneTextFile(path) (see below),
/// planning-scene YAML otherwise; relative mesh paths are relative to its folder.
PlanningScene loadPlanningScene(const std::string& path, const SceneLoadOptions& options = {});
/// Reads planning-scene YAML text; relative mesh paths are relative to `baseDirectory`.
/// `sourceName` names the text in messages ("<string>" when empty).
PlanningScene parsePlanningScene(const std::string& yaml, const std::string& baseDirectory,
                                 const SceneLoadOptions& options = {}, const std::string& sourceName = "");

// MoveIt's .scene text format: what MoveIt's "Export" / "Import" of a scene (PlanningScene::
// saveGeometryToStream, loadGeometryFromStream) and geometric_shapes' saveAsText and
// constructShapeFromText write and read. Whitespace-separated, but for two lines:
//   line 1            the scene's name (PlanningScene::name)
//   per object:
//     * ID            the rest of the line, trimmed, is the id (unique, not empty)
//     x y z / qx qy qz qw   the object pose X_FO (newer format only; see below)
//     N               the number of shapes (at least 1)
//     per shape:      its type and dimensions, then its pose X_OS ("x y z", "qx qy qz qw"), then
//                     a colour "r g b a" (read and ignored):
//                       box X Y Z (full edge lengths) | sphere R | cylinder R L | cone R L
//                       (radius first, unlike shape_msgs) | mesh V T, then V vertices "x y z",
//                       then T triangles "i j k" (0-based vertex indices)
//     S, then S times "NAME" and a pose    the subframes (newer format only; read and ignored)
//   .                 the end of the scene (anything after it is ignored, as MoveIt does)
// The format has two versions, told apart as MoveIt does: when the line after the first "* ID"
// line holds more than one word (the object pose's position) the file is the newer one with
// object poses and subframes; otherwise the older one (no object pose: identity; no subframes).
// A .scene file has no frames: its objects are in MoveIt's planning frame, the model frame, so
// each object's frameId is kModelFrame, which shapeWorldPoses resolves to the robot's root link
// (MoveIt's model frame is the root link or, with an SRDF virtual joint, the joint's parent frame,
// which the robot's root sits on). Cones become pyramids as in YAML; a mesh becomes an in-memory
// TriangleMesh (SceneShape::mesh); a plane is an error (not modelled). Numbers must be finite with
// magnitude at most geometry::range::kMaxCoordinate, sizes positive, quaternions of unit norm within
// tol::kSceneQuaternionNorm; every count is checked against the tokens left in the file before
// anything is allocated for it, and the shapes against SceneLoadOptions::maxShapes.
// Errors: std::invalid_argument, "planning scene '<file>', line <n>, object '<id>': <what>".

/// The frame of a .scene file's objects: the model frame, resolved to the robot's root link. Not
/// a valid ROS frame name, so it names no link and no frame of a YAML scene by accident.
inline const std::string kModelFrame = "<model frame>";

/// True for a path ending in .scene (any case): MoveIt's scene text format.
bool isSceneTextFile(const std::string& path);
/// Reads .scene text (see above); `sourceName` names it in messages ("<string>" when empty).
PlanningScene parseSceneText(const std::string& text, const SceneLoadOptions& options = {},
                             const std::string& sourceName = "");
/// The scene as .scene text in the newer format (object poses, no subframes, colour "0 0 0 0"),
/// numbers with 17 significant digits: parseSceneText (and MoveIt) read it back to the same
/// objects. Meshes are written inline: a mesh file is loaded (mesh_loader.h, with its scale), a
/// cone as its pyramid (so it reads back as a mesh). Throws std::invalid_argument naming the
/// object for what a .scene file cannot hold: an object in a frame other than kModelFrame, an id
/// with a line break or a space at either end, attached objects or allowed collisions.
std::string writeSceneText(const PlanningScene& scene);

/// The triangle mesh of the circumscribed pyramid of a cone along z (see the header comment).
/// Throws std::invalid_argument unless height, radius and maxDeviation are positive and finite.
TriangleMesh coneMesh(double height, double radius, double maxDeviation);

/// The scene as planning-scene YAML that loadPlanningScene reads back to the same objects, attached
/// objects (robot_state.attached_collision_objects) and allowed collisions (an
/// allowed_collision_matrix over the names of the pairs, symmetric; the default entries true for
/// `always`; pairs read back in the matrix's order, (A, B) possibly as (B, A)): each object with
/// its frame_id and id, no `pose` (shape poses are X_FS, the object pose folded in),
/// its primitives then its meshes (resource: the resolved absolute path; an in-memory mesh, a
/// cone's pyramid included, inline as vertices and triangles, so a cone reads back as its
/// pyramid), numbers with 17 significant digits, quaternions x y z w.
std::string writePlanningScene(const PlanningScene& scene);

/// A scene given as a URDF (MotionBenchMaker's kitchen and table_bars: fixed parts, doors and
/// sliding bars as links and joints) as a planning scene at the scene's configuration q: one
/// object per link with collision geometry, its id the link's name, in frame `frameId`, one shape
/// per collision element posed by forward kinematics (X_FS = X_FL(q) X_LG, the scene's base pose
/// included); the objects keep the identity pose, so an object's reference pose is its first
/// shape's, as for MotionBenchMaker's objects. `source` is the URDF's. Throws
/// std::invalid_argument naming the value for a q of the wrong size or with a non-finite entry.
PlanningScene planningSceneFromUrdf(const RobotModel& scene, const Eigen::Ref<const Eigen::VectorXd>& q,
                                    const std::string& frameId);

/// Frame names of a scene file mapped to robot link names, e.g. {"base_link", "panda_link0"}.
using FrameAliases = std::map<std::string, std::string>;

/// Parses "NAME=LINK" (the CLI's --frame-alias). Throws std::invalid_argument when malformed.
std::pair<std::string, std::string> parseFrameAlias(const std::string& text);

/// `aliases` with, for each SRDF virtual joint (srdf.h), its parent frame (MoveIt's model frame:
/// world, odom_combined...) mapped to its child link (the robot's root), so that scene objects
/// given in that frame need no alias of their own. An existing alias of the frame is kept (the
/// caller's wins, as does the first of two virtual joints with the same parent frame), and a
/// parent frame that is a link of `robot` is left to name that link.
FrameAliases withVirtualJointAliases(FrameAliases aliases, const std::vector<SrdfVirtualJoint>& virtualJoints,
                                     const RobotModel& robot);

/// World poses X_WS of every shape, result[object][shape] = X_WF * X_FS, where X_WF is the pose
/// of the robot link named by the object's frame (through `aliases` when it is a key there; else
/// the link of that name; else, for kModelFrame, the root link) at
/// configuration q (forward kinematics, with the robot's base pose). Throws
/// std::invalid_argument for a frame that is no link, naming the file, object and frame, listing
/// the robot's links and suggesting an alias; or for an alias whose target is no link.
std::vector<std::vector<Eigen::Isometry3d>> shapeWorldPoses(const PlanningScene& scene, const RobotModel& robot,
                                                            const Eigen::Ref<const Eigen::VectorXd>& q,
                                                            const FrameAliases& aliases = {});

}  // namespace deepcheck::robots
