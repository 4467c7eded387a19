// MoveIt's .scene text format read into a PlanningScene (moveit_scene.h: parseSceneText).
#include "deepcheck/robots/moveit_scene.h"

#include <deepcheck/geometry/input_range.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace {

struct Token {
  std::string text;
  int line = 0;  ///< 1-based
};

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// The lines of `text` ('\n' separated, a trailing '\r' dropped).
std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

/// The whitespace-separated tokens after the name line; the rest of a line after a "*" token is
/// one token (the object's id, trimmed), as MoveIt reads it.
std::vector<Token> tokenize(const std::vector<std::string>& lines) {
  std::vector<Token> tokens;
  for (std::size_t n = 1; n < lines.size(); ++n) {
    std::istringstream in(lines[n]);
    const int line = static_cast<int>(n) + 1;
    for (std::string word; in >> word;) {
      tokens.push_back({word, line});
      if (word != "*") continue;
      std::string rest;
      std::getline(in, rest);
      tokens.push_back({trimmed(rest), line});
    }
  }
  return tokens;
}

/// MoveIt's test: the newer format (with object poses and subframes) is the one whose line after
/// the first object's "* id" line holds several numbers (a position), the older one's a count.
bool newFormat(const std::vector<std::string>& lines) {
  for (std::size_t n = 1; n + 1 < lines.size(); ++n) {
    if (lines[n].empty() || lines[n][0] != '*') continue;
    return trimmed(lines[n + 1]).find_first_of(" \t") != std::string::npos;
  }
  return false;
}

class SceneTextReader {
 public:
  SceneTextReader(const std::string& text, const SceneLoadOptions& options, const std::string& source)
      : lines_(splitLines(text)), tokens_(tokenize(lines_)), options_(options), source_(source) {}

  PlanningScene read() {
    PlanningScene scene;
    scene.source = source_;
    scene.name = lines_.empty() ? "" : trimmed(lines_[0]);
    const bool withPoses = newFormat(lines_);
    std::map<std::string, int> ids;
    for (;;) {
      const Token& marker = next("'*' (an object) or '.' (the end of the scene)");
      if (marker.text == ".") return scene;
      if (marker.text != "*") {
        fail(marker, "unknown marker '" + marker.text + "': expected '*' (an object) or '.' (the end of the scene)");
      }
      SceneObject object = readObject(marker.line, withPoses);
      const auto [it, inserted] = ids.emplace(object.id, object.line);
      if (!inserted) fail(marker, "the id is used twice (first at line " + std::to_string(it->second) + ")");
      scene.objects.push_back(std::move(object));
      object_.clear();
    }
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    std::string where = "planning scene '" + source_ + "'";
    if (line > 0) where += ", line " + std::to_string(line);
    if (!object_.empty()) where += ", " + object_;
    throw std::invalid_argument(where + ": " + what);
  }
  [[noreturn]] void fail(const Token& token, const std::string& what) const { fail(token.line, what); }

  const Token& next(const std::string& what) {
    if (at_ < tokens_.size()) return tokens_[at_++];
    fail(static_cast<int>(lines_.size()), "the file ends where " + what + " was expected");
  }

  std::size_t remaining() const { return tokens_.size() - at_; }

  double number(const std::string& what) {
    const Token& t = next(what);
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(t.text.c_str(), &end);
    if (t.text.empty() || *end != '\0') fail(t, what + " must be a number, is '" + t.text + "'");
    if (!std::isfinite(value) || std::abs(value) > geometry::range::kMaxCoordinate) {
      std::ostringstream msg;
      msg << what << " must be finite with magnitude at most " << geometry::range::kMaxCoordinate << ", is '" << t.text
          << "'";
      fail(t, msg.str());
    }
    return value;
  }

  double positive(const std::string& what) {
    const int line = peekLine();
    const double value = number(what);
    if (!(value > 0.0)) {
      std::ostringstream msg;
      msg << what << " must be positive, is " << value;
      fail(line, msg.str());
    }
    return value;
  }

  int peekLine() const { return at_ < tokens_.size() ? tokens_[at_].line : static_cast<int>(lines_.size()); }

  /// A count (a non-negative integer) of at most `most`.
  std::size_t count(const std::string& what, std::size_t most) {
    const Token& t = next(what);
    char* end = nullptr;
    errno = 0;
    const unsigned long long value = std::strtoull(t.text.c_str(), &end, 10);
    if (t.text.empty() || t.text[0] == '-' || *end != '\0' || errno == ERANGE) {
      fail(t, what + " must be a count (0, 1, 2...), is '" + t.text + "'");
    }
    if (value > most) fail(t, what + " is " + t.text + ", more than " + std::to_string(most) + " (" + why_ + ")");
    return static_cast<std::size_t>(value);
  }

  /// "x y z" then the quaternion "x y z w", normalised (tol::kSceneQuaternionNorm).
  Eigen::Isometry3d pose(const std::string& what) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    for (int k = 0; k < 3; ++k) X.translation()[k] = number(what + " position[" + std::to_string(k) + "]");
    const int line = peekLine();
    double q[4];
    for (int k = 0; k < 4; ++k) q[k] = number(what + " orientation[" + std::to_string(k) + "]");
    Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);  // Eigen's constructor takes w first
    if (!(std::abs(rotation.norm() - 1.0) <= tol::kSceneQuaternionNorm)) {
      std::ostringstream msg;
      msg << what << " orientation [x y z w] = [" << q[0] << ", " << q[1] << ", " << q[2] << ", " << q[3]
          << "] has norm " << rotation.norm() << ", not 1 (within " << tol::kSceneQuaternionNorm << ")";
      fail(line, msg.str());
    }
    X.linear() = rotation.normalized().toRotationMatrix();
    return X;
  }

  SceneObject readObject(int line, bool withPoses) {
    SceneObject object;
    object.line = line;
    object.frameId = kModelFrame;
    object.id = next("the object's id").text;
    object_ = "object " + std::to_string(objectCount_++);
    if (object.id.empty()) fail(line, "the object's id is empty (expected '* ID')");
    object_ = "object '" + object.id + "'";
    if (withPoses) object.X_FO = pose("the object pose");
    why_ = "SceneLoadOptions::maxShapes = " + std::to_string(options_.maxShapes) + " shapes in all";
    const std::size_t shapes = count("the shape count", options_.maxShapes - shapeCount_);
    if (shapes == 0) fail(line, "the object has no shapes");
    shapeCount_ += shapes;
    for (std::size_t k = 0; k < shapes; ++k) {
      SceneShape shape = readShape(static_cast<int>(k));
      shape.X_FS = object.X_FO * pose(shape.name + " pose");
      for (const char* c : {"red", "green", "blue", "alpha"}) number(shape.name + " colour " + c);
      object.shapes.push_back(std::move(shape));
    }
    if (withPoses) readSubframes();
    return object;
  }

  /// Subframes (newer format): a count, then per subframe a name and a pose; read and ignored.
  void readSubframes() {
    why_ = "the tokens left in the file";
    const std::size_t n = count("the subframe count", remaining());
    for (std::size_t k = 0; k < n; ++k) {
      const std::string what = "subframe " + std::to_string(k);
      next(what + " name");
      pose(what);
    }
  }

  SceneShape readShape(int index) {
    const Token& type = next("shape " + std::to_string(index) + "'s type");
    SceneShape shape;
    shape.line = type.line;
    shape.name = "shape " + std::to_string(index) + " (" + type.text;
    const std::string& t = type.text;
    if (t == "box") {
      shape.geometry.type = GeometryType::Box;
      for (int k = 0; k < 3; ++k) shape.geometry.boxSize[k] = positive("box size " + std::string(1, "xyz"[k]));
    } else if (t == "sphere") {
      shape.geometry.type = GeometryType::Sphere;
      shape.geometry.radius = positive("sphere radius");
    } else if (t == "cylinder") {  // radius first, then length (geometric_shapes' order)
      shape.geometry.type = GeometryType::Cylinder;
      shape.geometry.radius = positive("cylinder radius");
      shape.geometry.length = positive("cylinder length");
    } else if (t == "cone") {
      const double radius = positive("cone radius");
      const double length = positive("cone length");
      setMesh(shape, coneMesh(length, radius, options_.coneMaxDeviation), "cone");
      shape.name += ", " + std::to_string(shape.mesh->vertices.size() - 1) + "-sided pyramid";
    } else if (t == "mesh") {
      setMesh(shape, readMesh(), "mesh");
      shape.name += ", " + std::to_string(shape.mesh->vertices.size()) + " vertices, " +
                    std::to_string(shape.mesh->triangles.size()) + " triangles";
    } else if (t == "plane") {
      fail(type, "shape " + std::to_string(index) + " is a plane: infinite planes are not modelled; use a thin box");
    } else {
      fail(type, "unknown shape type '" + t + "' (known: box, sphere, cylinder, cone, mesh)");
    }
    shape.name += ")";
    return shape;
  }

  void setMesh(SceneShape& shape, TriangleMesh mesh, const char* kind) const {
    shape.geometry.type = GeometryType::Mesh;
    mesh.source = source_ + " " + object_ + " " + kind;
    shape.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  }

  /// "V T", V vertices "x y z", T triangles "i j k" (0-based vertex indices).
  TriangleMesh readMesh() {
    const int line = peekLine();
    why_ = "three numbers each, and the file has " + std::to_string(remaining()) + " tokens left";
    const std::size_t vertices = count("the mesh's vertex count", remaining() / 3);
    const std::size_t afterCounts = remaining() == 0 ? 0 : remaining() - 1;  // the triangle count read
    if (3 * vertices > afterCounts) {
      fail(line, "the mesh has " + std::to_string(vertices) + " vertices, the file has " + std::to_string(afterCounts) +
                     " tokens left");
    }
    why_ = "three indices each, and the file has " + std::to_string(afterCounts - 3 * vertices) +
           " tokens left after the vertices";
    const std::size_t triangles = count("the mesh's triangle count", (afterCounts - 3 * vertices) / 3);
    if (vertices < 3 || triangles < 1) fail(line, "a mesh needs 3 vertices and a triangle or more");
    TriangleMesh mesh;
    for (std::size_t v = 0; v < vertices; ++v) {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k)
        p[k] = number("mesh vertex " + std::to_string(v) + " coordinate " + std::to_string(k));
      mesh.vertices.push_back(p);
    }
    why_ = "the mesh's last vertex index";
    for (std::size_t t = 0; t < triangles; ++t) {
      std::array<int, 3> triangle{};
      for (int k = 0; k < 3; ++k) {
        triangle[k] =
            static_cast<int>(count("mesh triangle " + std::to_string(t) + " index " + std::to_string(k), vertices - 1));
      }
      mesh.triangles.push_back(triangle);
    }
    return mesh;
  }

  std::vector<std::string> lines_;
  std::vector<Token> tokens_;
  std::size_t at_ = 0;
  const SceneLoadOptions& options_;
  std::string source_;
  std::string object_;  ///< "object 'box'", for messages; "" between objects
  std::string why_;     ///< why a count has the limit it has, for messages
  int objectCount_ = 0;
  std::size_t shapeCount_ = 0;
};

}  // namespace

bool isSceneTextFile(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find_first_of("/\\", dot) != std::string::npos) return false;
  std::string extension = path.substr(dot);
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".scene";
}

PlanningScene parseSceneText(const std::string& text, const SceneLoadOptions& options, const std::string& sourceName) {
  const std::string source = sourceName.empty() ? "<string>" : sourceName;
  if (!(options.coneMaxDeviation > 0.0) || !std::isfinite(options.coneMaxDeviation)) {
    throw std::invalid_argument("planning scene '" + source + "': coneMaxDeviation must be positive and finite");
  }
  return SceneTextReader(text, options, source).read();
}

}  // namespace deepcheck::robots
