// MoveIt's .scene text format out (moveit_scene.h: writeSceneText), in the form both MoveIt and
// parseSceneText read.
#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/moveit_scene.h"

#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace {

/// The colour MoveIt writes for an object without one (and ignores when reading).
constexpr const char* kNoColour = "0 0 0 0";

std::string numbers(std::initializer_list<double> xs) {
  std::string out;
  for (double x : xs) out += (out.empty() ? "" : " ") + formatNumber(x);
  return out;
}

/// "x y z" then "qx qy qz qw", one line each.
void writePose(std::ostringstream& out, const Eigen::Isometry3d& X) {
  const Eigen::Vector3d p = X.translation();
  const Eigen::Quaterniond q(X.rotation());
  out << numbers({p.x(), p.y(), p.z()}) << "\n" << numbers({q.x(), q.y(), q.z(), q.w()}) << "\n";
}

void writeMesh(std::ostringstream& out, const TriangleMesh& mesh) {
  out << "mesh\n" << mesh.vertices.size() << " " << mesh.triangles.size() << "\n";
  for (const Eigen::Vector3d& v : mesh.vertices) out << numbers({v.x(), v.y(), v.z()}) << "\n";
  for (const auto& t : mesh.triangles) out << t[0] << " " << t[1] << " " << t[2] << "\n";
}

/// The shape's type line and dimensions (geometric_shapes' saveAsText): a mesh file is read and
/// written inline, scaled; an in-memory mesh (a cone's pyramid) inline as it is.
void writeShape(std::ostringstream& out, const SceneShape& s) {
  const Geometry& g = s.geometry;
  switch (g.type) {
    case GeometryType::Box:
      out << "box\n" << numbers({g.boxSize.x(), g.boxSize.y(), g.boxSize.z()}) << "\n";
      return;
    case GeometryType::Sphere:
      out << "sphere\n" << numbers({g.radius}) << "\n";
      return;
    case GeometryType::Cylinder:
      out << "cylinder\n" << numbers({g.radius, g.length}) << "\n";
      return;
    case GeometryType::Mesh:
      writeMesh(out, s.mesh ? *s.mesh : loadMesh(g.meshPath, g.meshScale));
      return;
  }
}

/// Throws unless the scene has only what a .scene file can hold.
void checkWritable(const PlanningScene& scene) {
  const std::string what = "writing planning scene '" + scene.source + "' as a .scene file: ";
  if (!scene.attached.empty()) {
    throw std::invalid_argument(what + "attached object '" + scene.attached[0].object.id +
                                "': a .scene file holds no attached objects");
  }
  if (!scene.allowed.pairs.empty() || !scene.allowed.always.empty()) {
    throw std::invalid_argument(what + "a .scene file holds no allowed collisions");
  }
  for (const SceneObject& o : scene.objects) {
    if (o.id.find_first_of("\n\r") != std::string::npos || o.id.find_first_of(" \t") == 0 ||
        o.id.find_last_of(" \t") + 1 == o.id.size()) {
      throw std::invalid_argument(what + "object '" + o.id +
                                  "': an id in a .scene file is a line: no line breaks, no space at either end");
    }
    if (o.frameId == kModelFrame) continue;
    throw std::invalid_argument(what + "object '" + o.id + "' is in frame '" + o.frameId +
                                "': a .scene file has no frames, its objects are in the model frame");
  }
}

}  // namespace

std::string writeSceneText(const PlanningScene& scene) {
  checkWritable(scene);
  std::ostringstream out;
  std::string name = scene.name;
  for (char& c : name) c = c == '\n' || c == '\r' ? ' ' : c;
  out << name << "\n";
  for (const SceneObject& o : scene.objects) {
    out << "* " << o.id << "\n";
    writePose(out, o.X_FO);
    out << o.shapes.size() << "\n";
    const Eigen::Isometry3d X_OF = o.X_FO.inverse();
    for (const SceneShape& s : o.shapes) {
      writeShape(out, s);
      writePose(out, X_OF * s.X_FS);
      out << kNoColour << "\n";
    }
    out << "0\n";  // no subframes
  }
  out << ".\n";
  return out.str();
}

}  // namespace deepcheck::robots
