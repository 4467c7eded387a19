// Planning-scene YAML out (moveit_scene.h: writePlanningScene), in the form the loader reads.

#include "deepcheck/robots/moveit_scene.h"

#include "deepcheck/robots/format_number.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

namespace deepcheck::robots {

namespace {

std::string list(std::initializer_list<double> xs) {
  std::string out = "[";
  for (double x : xs) out += (out.size() > 1 ? ", " : "") + formatNumber(x);
  return out + "]";
}

/// A YAML double-quoted string.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

void writePose(std::ostringstream& out, const Eigen::Isometry3d& X) {
  const Eigen::Vector3d p = X.translation();
  const Eigen::Quaterniond q(X.rotation());
  out << "        - position: " << list({p.x(), p.y(), p.z()}) << "\n"
      << "          orientation: " << list({q.x(), q.y(), q.z(), q.w()}) << "\n";
}

/// "type: box\n dimensions: [...]" of a primitive.
std::string primitive(const Geometry& g) {
  switch (g.type) {
    case GeometryType::Box: return "type: box, dimensions: " + list({g.boxSize.x(), g.boxSize.y(), g.boxSize.z()});
    case GeometryType::Sphere: return "type: sphere, dimensions: " + list({g.radius});
    case GeometryType::Cylinder: return "type: cylinder, dimensions: " + list({g.length, g.radius});
    case GeometryType::Mesh: break;
  }
  return "";
}

void writeObject(std::ostringstream& out, const SceneObject& o) {
  std::vector<const SceneShape*> primitives, meshes;
  for (const SceneShape& s : o.shapes) {
    if (s.geometry.type != GeometryType::Mesh) {
      primitives.push_back(&s);
    } else if (s.geometry.meshPath.empty()) {
      throw std::invalid_argument("writing planning scene: object '" + o.id + "', " + s.name +
                                  ": an in-memory mesh (a cone) has no file form");
    } else {
      meshes.push_back(&s);
    }
  }
  out << "    - header:\n        frame_id: " << quoted(o.frameId) << "\n      id: " << quoted(o.id) << "\n";
  if (!primitives.empty()) {
    out << "      primitives:\n";
    for (const SceneShape* s : primitives) out << "        - {" << primitive(s->geometry) << "}\n";
    out << "      primitive_poses:\n";
    for (const SceneShape* s : primitives) writePose(out, s->X_FS);
  }
  if (!meshes.empty()) {
    out << "      meshes:\n";
    for (const SceneShape* s : meshes) {
      const Eigen::Vector3d& k = s->geometry.meshScale;
      out << "        - {resource: " << quoted(s->geometry.meshPath) << ", scale: " << list({k.x(), k.y(), k.z()}) << "}\n";
    }
    out << "      mesh_poses:\n";
    for (const SceneShape* s : meshes) writePose(out, s->X_FS);
  }
}

}  // namespace

std::string writePlanningScene(const PlanningScene& scene) {
  std::ostringstream out;
  out << "world:\n  collision_objects:" << (scene.objects.empty() ? " []" : "") << "\n";
  for (const SceneObject& o : scene.objects) writeObject(out, o);
  return out.str();
}

}  // namespace deepcheck::robots
