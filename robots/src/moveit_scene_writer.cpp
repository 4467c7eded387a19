// Planning-scene YAML out (moveit_scene.h: writePlanningScene), in the form the loader reads.

#include "deepcheck/robots/moveit_scene.h"

#include "deepcheck/robots/format_number.h"

#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace deepcheck::robots {

namespace {

std::string list(std::initializer_list<double> xs) {
  std::string out = "[";
  for (double x : xs) out += (out.size() > 1 ? ", " : "") + formatNumber(x);
  return out + "]";
}

/// A YAML double-quoted string.
std::string yamlQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

/// A pose as an entry of a list whose "- " starts at column indent.size().
void writePose(std::ostringstream& out, const std::string& indent, const Eigen::Isometry3d& X) {
  const Eigen::Vector3d p = X.translation();
  const Eigen::Quaterniond q(X.rotation());
  out << indent << "- position: " << list({p.x(), p.y(), p.z()}) << "\n"
      << indent << "  orientation: " << list({q.x(), q.y(), q.z(), q.w()}) << "\n";
}

/// "type: box\n dimensions: [...]" of a primitive.
std::string primitive(const Geometry& g) {
  switch (g.type) {
    case GeometryType::Box:
      return "type: box, dimensions: " + list({g.boxSize.x(), g.boxSize.y(), g.boxSize.z()});
    case GeometryType::Sphere:
      return "type: sphere, dimensions: " + list({g.radius});
    case GeometryType::Cylinder:
      return "type: cylinder, dimensions: " + list({g.length, g.radius});
    case GeometryType::Mesh:
      break;
  }
  return "";
}

/// A mesh entry: its file (resolved path and scale), or an in-memory mesh inline.
void writeMesh(std::ostringstream& out, const std::string& entry, const SceneShape& s) {
  if (!s.mesh) {
    const Eigen::Vector3d& k = s.geometry.meshScale;
    out << entry << "- {resource: " << yamlQuoted(s.geometry.meshPath) << ", scale: " << list({k.x(), k.y(), k.z()})
        << "}\n";
    return;
  }
  out << entry << "- vertices:\n";
  for (const Eigen::Vector3d& v : s.mesh->vertices) out << entry << "    - " << list({v.x(), v.y(), v.z()}) << "\n";
  out << entry << "  triangles:\n";
  for (const auto& t : s.mesh->triangles) {
    out << entry << "    - {vertex_indices: [" << t[0] << ", " << t[1] << ", " << t[2] << "]}\n";
  }
}

/// A collision object as a YAML map: its first key after `first` ("    - " for a list entry), the
/// others at column indent.size() (first.size() == indent.size()).
void writeObject(std::ostringstream& out, const std::string& first, const std::string& indent, const SceneObject& o) {
  std::vector<const SceneShape*> primitives, meshes;
  for (const SceneShape& s : o.shapes) (s.geometry.type == GeometryType::Mesh ? meshes : primitives).push_back(&s);
  const std::string entry = indent + "  ";
  out << first << "header:\n"
      << indent << "  frame_id: " << yamlQuoted(o.frameId) << "\n"
      << indent << "id: " << yamlQuoted(o.id) << "\n";
  if (!primitives.empty()) {
    out << indent << "primitives:\n";
    for (const SceneShape* s : primitives) out << entry << "- {" << primitive(s->geometry) << "}\n";
    out << indent << "primitive_poses:\n";
    for (const SceneShape* s : primitives) writePose(out, entry, s->X_FS);
  }
  if (!meshes.empty()) {
    out << indent << "meshes:\n";
    for (const SceneShape* s : meshes) writeMesh(out, entry, *s);
    out << indent << "mesh_poses:\n";
    for (const SceneShape* s : meshes) writePose(out, entry, s->X_FS);
  }
}

/// ["a", "b"] of names.
std::string nameList(const std::vector<std::string>& names) {
  std::string out = "[";
  for (const std::string& n : names) out += (out.size() > 1 ? ", " : "") + yamlQuoted(n);
  return out + "]";
}

/// [true, false] of flags.
std::string boolList(const std::vector<bool>& flags) {
  std::string out = "[";
  for (const bool f : flags) out += std::string(out.size() > 1 ? ", " : "") + (f ? "true" : "false");
  return out + "]";
}

void writeAttached(std::ostringstream& out, const std::vector<AttachedObject>& attached) {
  if (attached.empty()) return;
  out << "robot_state:\n  attached_collision_objects:\n";
  for (const AttachedObject& a : attached) {
    out << "    - link_name: " << yamlQuoted(a.linkName) << "\n      object:\n";
    writeObject(out, "        ", "        ", a.object);
    out << "      touch_links: " << nameList(a.touchLinks) << "\n";
  }
}

/// The matrix over the names of the pairs (in order of first appearance), symmetric, true for
/// the pairs; the default entries true for `always`.
void writeAllowed(std::ostringstream& out, const AllowedCollisions& allowed) {
  if (allowed.pairs.empty() && allowed.always.empty()) return;
  std::vector<std::string> names;
  std::map<std::string, std::size_t> index;
  for (const auto& [a, b] : allowed.pairs) {
    for (const std::string& n : {a, b}) {
      if (index.emplace(n, names.size()).second) names.push_back(n);
    }
  }
  std::vector<std::vector<bool>> enabled(names.size(), std::vector<bool>(names.size(), false));
  for (const auto& [a, b] : allowed.pairs) {
    enabled[index[a]][index[b]] = true;
    enabled[index[b]][index[a]] = true;
  }
  out << "allowed_collision_matrix:\n  entry_names: " << nameList(names)
      << "\n  entry_values:" << (names.empty() ? " []" : "") << "\n";
  for (const std::vector<bool>& row : enabled) out << "    - enabled: " << boolList(row) << "\n";
  out << "  default_entry_names: " << nameList(allowed.always)
      << "\n  default_entry_values: " << boolList(std::vector<bool>(allowed.always.size(), true)) << "\n";
}

}  // namespace

std::string writePlanningScene(const PlanningScene& scene) {
  std::ostringstream out;
  if (!scene.name.empty()) out << "name: " << yamlQuoted(scene.name) << "\n";
  writeAttached(out, scene.attached);
  writeAllowed(out, scene.allowed);
  out << "world:\n  collision_objects:" << (scene.objects.empty() ? " []" : "") << "\n";
  for (const SceneObject& o : scene.objects) writeObject(out, "    - ", "      ", o);
  return out.str();
}

}  // namespace deepcheck::robots
