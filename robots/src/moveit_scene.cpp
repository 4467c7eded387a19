// Reading a MoveIt planning-scene YAML into a PlanningScene (moveit_scene.h).
#include "deepcheck/robots/moveit_scene.h"

#include "deepcheck/robots/package_path.h"
#include "moveit_scene_acm.h"
#include "moveit_scene_inline_mesh.h"
#include "scene_yaml.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace {

using scene_yaml::Context;
using scene_yaml::lineOf;
using scene_yaml::readNumbers;
using scene_yaml::readPose;
using scene_yaml::readString;
using scene_yaml::required;

struct Reader {
  Context ctx;
  std::string baseDirectory;
  std::vector<std::string> roots;
  double coneMaxDeviation = 0.0;
  std::size_t maxShapes = 0;
  std::size_t shapeCount = 0;  ///< shapes read so far, aliased ones counted each time
  std::size_t meshBudget = 0;  ///< inline mesh vertices and triangles the scene may still hold
};

/// Throws when `more` entries of `list` (objects or shapes) would take the scene past
/// SceneLoadOptions::maxShapes. Called before they are read, so that YAML aliases repeating a
/// list are stopped as soon as their expansion passes the limit.
void checkShapeCount(const Reader& r, const YAML::Node& list, std::size_t more, const char* what) {
  if (r.shapeCount + more <= r.maxShapes) return;
  r.ctx.fail(list, std::to_string(r.shapeCount + more) + " " + what + " so far (YAML aliases counted as expanded), " +
                       "more than SceneLoadOptions::maxShapes = " + std::to_string(r.maxShapes));
}

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// A primitive type as shape_msgs/SolidPrimitive numbers it, with its dimension names.
struct PrimitiveType {
  const char* name;
  const char* number;
  std::vector<const char*> dimensions;
};

const std::vector<PrimitiveType>& primitiveTypes() {
  static const std::vector<PrimitiveType> types = {
      {"box", "1", {"x", "y", "z"}},
      {"sphere", "2", {"radius"}},
      {"cylinder", "3", {"height", "radius"}},
      {"cone", "4", {"height", "radius"}},
  };
  return types;
}

const PrimitiveType& readPrimitiveType(const Context& ctx, const YAML::Node& node) {
  const std::string text = lowercase(readString(ctx, node, "primitive type"));
  for (const PrimitiveType& t : primitiveTypes()) {
    if (text == t.name || text == t.number) return t;
  }
  ctx.fail(node, "unknown primitive type '" + node.Scalar() +
                     "' (known: box, sphere, cylinder, cone, or shape_msgs' numbers 1 to 4)");
}

SceneShape readPrimitive(Reader& r, const YAML::Node& node, int index) {
  const Context& ctx = r.ctx;
  scene_yaml::checkKeys(ctx, node, "a primitive", {"type", "dimensions"});
  const PrimitiveType& type = readPrimitiveType(ctx, required(ctx, node, "type"));
  const YAML::Node dimensionsNode = required(ctx, node, "dimensions");
  std::string names;
  for (const char* n : type.dimensions) names += (names.empty() ? "" : ", ") + std::string(n);
  if (dimensionsNode.IsSequence() && dimensionsNode.size() != type.dimensions.size()) {
    ctx.fail(dimensionsNode, std::string("a ") + type.name + " needs " + std::to_string(type.dimensions.size()) +
                                 " dimensions [" + names + "], has " + std::to_string(dimensionsNode.size()));
  }
  const std::vector<double> d = readNumbers(ctx, dimensionsNode, "dimensions");
  for (size_t i = 0; i < d.size(); ++i) {
    if (d[i] > 0.0) continue;
    std::ostringstream msg;
    msg << type.name << " " << type.dimensions[i] << " must be positive, is " << d[i];
    ctx.fail(dimensionsNode[i], msg.str());
  }
  SceneShape shape;
  shape.name = "primitive " + std::to_string(index) + " (" + type.name;
  const std::string name = type.name;
  if (name == "box") {
    shape.geometry.type = GeometryType::Box;
    shape.geometry.boxSize = Eigen::Vector3d(d[0], d[1], d[2]);
  } else if (name == "sphere") {
    shape.geometry.type = GeometryType::Sphere;
    shape.geometry.radius = d[0];
  } else if (name == "cylinder") {
    shape.geometry.type = GeometryType::Cylinder;
    shape.geometry.length = d[0];
    shape.geometry.radius = d[1];
  } else {
    shape.geometry.type = GeometryType::Mesh;
    auto mesh = std::make_shared<TriangleMesh>(coneMesh(d[0], d[1], r.coneMaxDeviation));
    mesh->source = r.ctx.source + " " + r.ctx.object + " cone";
    shape.name += ", " + std::to_string(mesh->vertices.size() - 1) + "-sided pyramid";
    shape.mesh = std::move(mesh);
  }
  shape.name += ")";
  return shape;
}

/// The value of exactly one of two synonymous keys (e.g. resource / filename); undefined when
/// neither is given.
YAML::Node oneOf(const Context& ctx, const YAML::Node& node, const char* a, const char* b) {
  const YAML::Node first = node[a];
  const YAML::Node second = node[b];
  if (first.IsDefined() && second.IsDefined()) {
    ctx.fail(node, std::string("give either '") + a + "' or '" + b + "', not both");
  }
  return first.IsDefined() ? first : second;
}

/// A shape_msgs/Mesh given inline: an in-memory mesh, as a cone's.
SceneShape readInlineMeshShape(Reader& r, const YAML::Node& node, int index) {
  scene_yaml::checkKeys(r.ctx, node, "an inline mesh", {"vertices", "triangles"});
  auto mesh = std::make_shared<TriangleMesh>(readInlineMesh(r.ctx, node, r.meshBudget));
  mesh->source = r.ctx.source + " " + r.ctx.object + " mesh " + std::to_string(index);
  SceneShape shape;
  shape.geometry.type = GeometryType::Mesh;
  shape.name = "mesh " + std::to_string(index) + " (inline, " + std::to_string(mesh->vertices.size()) + " vertices, " +
               std::to_string(mesh->triangles.size()) + " triangles)";
  shape.mesh = std::move(mesh);
  return shape;
}

SceneShape readMesh(Reader& r, const YAML::Node& node, int index) {
  const Context& ctx = r.ctx;
  if (isInlineMesh(node)) return readInlineMeshShape(r, node, index);
  scene_yaml::checkKeys(ctx, node, "a mesh", {"resource", "filename", "scale", "dimensions"});
  const YAML::Node uriNode = oneOf(ctx, node, "resource", "filename");
  if (!uriNode.IsDefined()) ctx.fail(node, "a mesh needs 'resource' (or 'filename'), or 'vertices' and 'triangles'");
  SceneShape shape;
  shape.geometry.type = GeometryType::Mesh;
  shape.geometry.meshUri = readString(ctx, uriNode, "mesh resource");
  const YAML::Node scaleNode = oneOf(ctx, node, "scale", "dimensions");
  if (scaleNode.IsDefined()) {
    shape.geometry.meshScale = scene_yaml::readVector3(ctx, scaleNode, "mesh scale");
    if (!(shape.geometry.meshScale.array() > 0.0).all()) {
      ctx.fail(scaleNode, "mesh scale entries must be positive");
    }
  }
  shape.geometry.meshPath = resolveUriOrThrow(shape.geometry.meshUri, r.roots, r.baseDirectory,
                                              ctx.where(uriNode) + ", mesh " + std::to_string(index));
  shape.name =
      "mesh " + std::to_string(index) + " (" + std::filesystem::path(shape.geometry.meshPath).filename().string() + ")";
  return shape;
}

using ShapeReader = SceneShape (*)(Reader&, const YAML::Node&, int);

/// Appends the shapes listed under `listKey`, posed by the entries of `posesKey`.
void readShapes(Reader& r, const YAML::Node& object, const char* listKey, const char* posesKey, ShapeReader readShape,
                SceneObject& out) {
  const Context& ctx = r.ctx;
  const YAML::Node list = object[listKey];
  const YAML::Node poses = object[posesKey];
  const bool haveList = list.IsDefined() && !list.IsNull();
  const bool havePoses = poses.IsDefined() && !poses.IsNull();
  if (!haveList && !havePoses) return;
  if (!haveList) ctx.fail(poses, std::string("'") + posesKey + "' without '" + listKey + "'");
  if (!list.IsSequence()) ctx.fail(list, std::string("'") + listKey + "' must be a list");
  if (!havePoses && list.size() > 0) {
    ctx.fail(list, std::string("missing '") + posesKey + "': every entry of '" + listKey + "' needs a pose");
  }
  if (havePoses && (!poses.IsSequence() || poses.size() != list.size())) {
    ctx.fail(poses, std::string("'") + posesKey + "' must be a list with one pose per entry of '" + listKey + "' (" +
                        std::to_string(list.size()) + ")");
  }
  checkShapeCount(r, list, list.size(), "shapes");
  r.shapeCount += list.size();
  for (size_t i = 0; i < list.size(); ++i) {
    SceneShape shape = readShape(r, list[i], static_cast<int>(i));
    const Eigen::Isometry3d X_OS = readPose(ctx, poses[i], std::string(posesKey) + "[" + std::to_string(i) + "]");
    shape.X_FS = out.X_FO * X_OS;
    shape.line = lineOf(list[i]);
    out.shapes.push_back(std::move(shape));
  }
}

/// CollisionObject.operation ADD as `ros2 topic echo` prints a `byte` field (Python's bytes).
constexpr const char* kEchoedAdd = "b'\\x00'";

/// Fails when `key` holds a non-empty list: a feature deepcheck does not model.
void rejectNonEmpty(const Context& ctx, const YAML::Node& node, const char* key, const char* why) {
  const YAML::Node value = node[key];
  if (!value.IsDefined() || value.IsNull()) return;
  if (value.IsSequence() && value.size() == 0) return;
  ctx.fail(value, std::string("'") + key + "' is not supported: " + why);
}

/// A collision object; `label` names it in messages ("object", "attached object").
SceneObject readObject(Reader& r, const YAML::Node& node, int index, const std::string& label = "object") {
  Context& ctx = r.ctx;
  ctx.object = label + " " + std::to_string(index);
  SceneObject object;
  object.line = lineOf(node);
  const YAML::Node idNode = required(ctx, node, "id");
  object.id = readString(ctx, idNode, "id");
  if (object.id.empty()) ctx.fail(idNode, "the id is empty");
  ctx.object = label + " '" + object.id + "'";
  scene_yaml::checkKeys(ctx, node, "a collision object",
                        {"header", "id", "pose", "type", "primitives", "primitive_poses", "meshes", "mesh_poses",
                         "planes", "plane_poses", "subframe_names", "subframe_poses", "operation"});
  const YAML::Node header = required(ctx, node, "header");
  scene_yaml::checkKeys(ctx, header, "header", {"frame_id", "seq", "stamp"});
  const YAML::Node frameNode = required(ctx, header, "frame_id");
  object.frameId = readString(ctx, frameNode, "header.frame_id");
  if (object.frameId.empty()) ctx.fail(frameNode, "header.frame_id is empty");
  const YAML::Node operation = node["operation"];
  if (operation.IsDefined()) {
    const std::string op = lowercase(readString(ctx, operation, "operation"));
    if (op != "add" && op != "0" && op != kEchoedAdd) {
      ctx.fail(operation,
               "operation '" + operation.Scalar() + "' is not supported: a scene file can only add objects (add, 0)");
    }
  }
  const YAML::Node pose = node["pose"];
  if (pose.IsDefined() && !pose.IsNull()) object.X_FO = readPose(ctx, pose, "pose");
  rejectNonEmpty(ctx, node, "planes", "infinite planes are not modelled; use a thin box");
  rejectNonEmpty(ctx, node, "plane_poses", "infinite planes are not modelled; use a thin box");
  readShapes(r, node, "primitives", "primitive_poses", readPrimitive, object);
  readShapes(r, node, "meshes", "mesh_poses", readMesh, object);
  if (object.shapes.empty()) ctx.fail(node, "the object has no primitives and no meshes");
  return object;
}

/// fixed_frame_transforms: only identities are accepted (see moveit_scene.h).
void readFixedFrameTransforms(Reader& r, const YAML::Node& list) {
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) r.ctx.fail(list, "'fixed_frame_transforms' must be a list");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string what = "fixed_frame_transforms[" + std::to_string(i) + "]";
    scene_yaml::checkKeys(r.ctx, list[i], what.c_str(), {"header", "child_frame_id", "transform"});
    const Eigen::Isometry3d X =
        scene_yaml::readTransform(r.ctx, required(r.ctx, list[i], "transform"), what + ".transform");
    if (!X.isApprox(Eigen::Isometry3d::Identity(), 0.0)) {
      r.ctx.fail(list[i], what +
                              " is not the identity; frames other than robot links are not "
                              "supported (map the frame to a link with a frame alias)");
    }
  }
}

/// world.octomap (octomap_msgs/OctomapWithPose: header, origin, octomap {header, binary, id,
/// resolution, data}): accepted when the octomap holds no data, as MoveIt and `ros2 topic echo`
/// write it for a scene without a sensor (MoveIt, too, ignores an octomap whose data is empty).
void readOctomap(const Context& ctx, const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return;
  scene_yaml::checkKeys(ctx, node, "world.octomap", {"header", "origin", "octomap"});
  const YAML::Node map = node["octomap"];
  if (!map.IsDefined() || map.IsNull()) return;
  scene_yaml::checkKeys(ctx, map, "world.octomap.octomap", {"header", "binary", "id", "resolution", "data"});
  const YAML::Node data = map["data"];
  if (!data.IsDefined() || data.IsNull()) return;
  if (data.IsSequence() && data.size() == 0) return;
  ctx.fail(data, "an octomap with data is not supported: give the obstacles as collision objects");
}

/// The ids read so far, with their lines: an id names one object, in the world or attached.
using IdLines = std::map<std::string, int>;

void claimId(const Reader& r, IdLines& ids, const SceneObject& object, const YAML::Node& node) {
  const auto [it, inserted] = ids.emplace(object.id, object.line);
  if (!inserted) {
    r.ctx.fail(node, "the id is used twice (first at line " + std::to_string(it->second) + ")");
  }
}

/// A list that may be absent or empty (undefined node: none); anything else but a list fails.
bool readList(const Context& ctx, const YAML::Node& list, const char* key) {
  if (!list.IsDefined() || list.IsNull()) return false;
  if (!list.IsSequence()) ctx.fail(list, std::string("'") + key + "' must be a list");
  return list.size() > 0;
}

/// One moveit_msgs/AttachedCollisionObject; detach_posture and weight are accepted and ignored.
AttachedObject readAttached(Reader& r, const YAML::Node& node, int index) {
  Context& ctx = r.ctx;
  ctx.object = "attached object " + std::to_string(index);
  scene_yaml::checkKeys(ctx, node, "an attached collision object",
                        {"link_name", "object", "touch_links", "detach_posture", "weight"});
  AttachedObject attached;
  attached.line = lineOf(node);
  const YAML::Node linkNode = required(ctx, node, "link_name");
  attached.linkName = readString(ctx, linkNode, "link_name");
  if (attached.linkName.empty()) ctx.fail(linkNode, "link_name is empty");
  attached.object = readObject(r, required(ctx, node, "object"), index, "attached object");
  const YAML::Node touch = node["touch_links"];
  if (readList(ctx, touch, "touch_links")) {
    for (std::size_t k = 0; k < touch.size(); ++k) {
      attached.touchLinks.push_back(readString(ctx, touch[k], "touch_links[" + std::to_string(k) + "]"));
    }
  }
  return attached;
}

/// robot_state (moveit_msgs/RobotState): its attached_collision_objects; the joint states are
/// accepted and ignored (the configuration is the caller's).
void readRobotState(Reader& r, const YAML::Node& state, IdLines& ids, PlanningScene& scene) {
  if (!state.IsDefined() || state.IsNull()) return;
  scene_yaml::checkKeys(r.ctx, state, "robot_state",
                        {"joint_state", "multi_dof_joint_state", "attached_collision_objects", "is_diff"});
  const YAML::Node list = state["attached_collision_objects"];
  if (!readList(r.ctx, list, "attached_collision_objects")) return;
  checkShapeCount(r, list, list.size(), "objects");  // each object has a shape
  for (std::size_t i = 0; i < list.size(); ++i) {
    AttachedObject attached = readAttached(r, list[i], static_cast<int>(i));
    claimId(r, ids, attached.object, list[i]);
    scene.attached.push_back(std::move(attached));
  }
  r.ctx.object.clear();
}

PlanningScene readScene(Reader& r, const YAML::Node& root) {
  if (!root.IsMap()) r.ctx.fail(root, "expected a map with 'world' (a MoveIt planning scene)");
  scene_yaml::checkKeys(r.ctx, root, "the planning scene",
                        {"world", "name", "robot_state", "robot_model_name", "fixed_frame_transforms",
                         "allowed_collision_matrix", "link_padding", "link_scale", "object_colors", "is_diff"});
  readFixedFrameTransforms(r, root["fixed_frame_transforms"]);
  PlanningScene scene;
  scene.source = r.ctx.source;
  const YAML::Node name = root["name"];
  if (name.IsDefined() && !name.IsNull()) scene.name = readString(r.ctx, name, "name");
  IdLines ids;
  readRobotState(r, root["robot_state"], ids, scene);
  scene.allowed = readAllowedCollisions(r.ctx, root["allowed_collision_matrix"]);
  const YAML::Node world = required(r.ctx, root, "world");
  scene_yaml::checkKeys(r.ctx, world, "world", {"collision_objects", "octomap"});
  readOctomap(r.ctx, world["octomap"]);
  const YAML::Node objects = world["collision_objects"];
  if (!readList(r.ctx, objects, "collision_objects")) return scene;
  checkShapeCount(r, objects, objects.size(), "collision objects");  // each object has a shape
  for (size_t i = 0; i < objects.size(); ++i) {
    SceneObject object = readObject(r, objects[i], static_cast<int>(i));
    claimId(r, ids, object, objects[i]);
    scene.objects.push_back(std::move(object));
  }
  return scene;
}

}  // namespace

int PlanningScene::objectIndex(const std::string& id) const {
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].id == id) return static_cast<int>(i);
  }
  return -1;
}

PlanningScene parsePlanningScene(const std::string& yaml, const std::string& baseDirectory,
                                 const SceneLoadOptions& options, const std::string& sourceName) {
  Reader r;
  r.ctx.source = sourceName.empty() ? "<string>" : sourceName;
  r.baseDirectory = baseDirectory;
  r.roots = packageRoots(options.packageRoots, options.useRosPackagePath);
  r.coneMaxDeviation = options.coneMaxDeviation;
  r.maxShapes = options.maxShapes;
  r.meshBudget = options.maxInlineMeshElements;
  if (!(options.coneMaxDeviation > 0.0) || !std::isfinite(options.coneMaxDeviation)) {
    throw std::invalid_argument("planning scene '" + r.ctx.source + "': coneMaxDeviation must be positive and finite");
  }
  try {
    return readScene(r, scene_yaml::loadYaml(yaml, r.ctx.source));
  } catch (const YAML::Exception& e) {
    std::string message = "planning scene '" + r.ctx.source + "'";
    if (!e.mark.is_null()) message += ", line " + std::to_string(e.mark.line + 1);
    if (!r.ctx.object.empty()) message += ", " + r.ctx.object;
    throw std::invalid_argument(message + ": malformed YAML: " + e.msg);
  }
}

PlanningScene loadPlanningScene(const std::string& path, const SceneLoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec)) {
    throw std::invalid_argument("planning scene '" + path + "': cannot read the file");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (isSceneTextFile(path)) return parseSceneText(buffer.str(), options, path);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  return parsePlanningScene(buffer.str(), folder, options, path);
}

}  // namespace deepcheck::robots
