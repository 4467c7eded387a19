#include "deepcheck/robots/mesh_loader.h"

#include "deepcheck/robots/tolerances.h"

#include "collada_check.h"
#include "in_quotes.h"
#include "obj_check.h"

#include <deepcheck/geometry/input_range.h>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace deepcheck::robots {

using detail::inQuotes;

namespace {

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4,  //
      m.b1, m.b2, m.b3, m.b4,     //
      m.c1, m.c2, m.c3, m.c4,     //
      m.d1, m.d2, m.d3, m.d4;
  return out;
}

std::string format(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

/// Merges the meshes instanced by the node tree, welding identical positions.
class Merger {
 public:
  Merger(const aiScene& scene, const Eigen::Vector3d& scale, TriangleMesh& out)
      : scene_(scene), scale_(scale), out_(out) {}

  /// Adds the meshes of the tree under `root`, depth first. The walk keeps its own stack: the
  /// depth of a node tree read from a binary format is not bounded.
  void addTree(const aiNode& root) {
    std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> pending{{&root, Eigen::Matrix4d::Identity()}};
    while (!pending.empty()) {
      const auto [node, parent] = pending.back();
      pending.pop_back();
      const Eigen::Matrix4d X = parent * toEigen(node->mTransformation);
      addNodeMeshes(*node, X);
      for (unsigned c = node->mNumChildren; c-- > 0;) pending.emplace_back(node->mChildren[c], X);
    }
  }

 private:
  /// The meshes of one node, placed by X (its accumulated transform).
  void addNodeMeshes(const aiNode& node, const Eigen::Matrix4d& X) {
    // Scale after the node transforms: the URDF scale applies to the file's frame.
    const Eigen::Matrix3d A = scale_.asDiagonal() * X.topLeftCorner<3, 3>();
    const Eigen::Vector3d b = scale_.cwiseProduct(X.topRightCorner<3, 1>());
    const bool mirrored = A.determinant() < 0.0;
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      addMesh(*scene_.mMeshes[node.mMeshes[i]], A, b, mirrored);
    }
  }

  void addMesh(const aiMesh& mesh, const Eigen::Matrix3d& A, const Eigen::Vector3d& b, bool mirrored) {
    std::vector<int> index(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const Eigen::Vector3d x = A * Eigen::Vector3d(p.x, p.y, p.z) + b;
      if (!(x.cwiseAbs().maxCoeff() <= geometry::range::kMaxCoordinate)) {
        std::ostringstream msg;
        msg << "mesh file " << inQuotes(out_.source) << ": vertex " << v << " of mesh " << inQuotes(mesh.mName.C_Str())
            << " (" << p.x << " " << p.y << " " << p.z << ") is at (" << format(x)
            << ") after the node transforms and the scale (" << format(scale_) << "); coordinates up to "
            << geometry::range::kMaxCoordinate << " are supported";
        throw std::invalid_argument(msg.str());
      }
      const std::array<double, 3> key{x.x(), x.y(), x.z()};
      auto [it, inserted] = weld_.emplace(key, static_cast<int>(out_.vertices.size()));
      if (inserted) out_.vertices.push_back(x);
      index[v] = it->second;
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      std::array<int, 3> t{index[face.mIndices[0]], index[face.mIndices[1]], index[face.mIndices[2]]};
      if (mirrored) std::swap(t[1], t[2]);
      out_.triangles.push_back(t);
    }
  }

  const aiScene& scene_;
  Eigen::Vector3d scale_;
  TriangleMesh& out_;
  std::map<std::array<double, 3>, int> weld_;
};

/// For an STL file assimp could not read, what is wrong with it as a binary STL ("" if nothing
/// is visibly wrong): assimp's own message ("Failed to determine STL storage representation")
/// does not say that the file is truncated.
std::string binaryStlHint(const std::string& path) {
  namespace fs = std::filesystem;
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".stl") return "";
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return "";
  std::ifstream in(path, std::ios::binary);
  char header[84] = {};
  in.read(header, sizeof header);
  if (std::string(header, 5) == "solid") return "";  // ASCII: assimp's message is specific
  if (size < 84) {
    return " (" + std::to_string(size) + " bytes: shorter than the 84-byte binary STL header)";
  }
  std::uint32_t count = 0;
  std::memcpy(&count, header + 80, 4);
  const std::uintmax_t expected = 84 + 50 * static_cast<std::uintmax_t>(count);
  if (expected == size) return "";
  return " (as binary STL: the header declares " + std::to_string(count) + " triangles, " + std::to_string(expected) +
         " bytes, but the file has " + std::to_string(size) + " bytes: truncated or corrupt)";
}

}  // namespace

int removeDegenerateTriangles(TriangleMesh& mesh) {
  const double diagonal = mesh.boundingBoxDiagonal();
  const double minHeight = tol::kDegenerateTriangleRelative * diagonal;
  const int before = static_cast<int>(mesh.triangles.size());
  std::vector<std::array<int, 3>> kept;
  kept.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    // Height over the longest edge = 2 * area / longest edge: small exactly when the triangle is
    // a needle or a sliver, whatever its size.
    const double height = longest > 0.0 ? (b - a).cross(c - a).norm() / longest : 0.0;
    if (height <= minHeight) continue;
    kept.push_back(t);
  }
  mesh.triangles.swap(kept);

  // Drop unused vertices and renumber.
  std::vector<int> newIndex(mesh.vertices.size(), -1);
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(mesh.vertices.size());
  for (auto& t : mesh.triangles) {
    for (int& i : t) {
      if (newIndex[i] < 0) {
        newIndex[i] = static_cast<int>(vertices.size());
        vertices.push_back(mesh.vertices[i]);
      }
      i = newIndex[i];
    }
  }
  mesh.vertices.swap(vertices);
  return before - static_cast<int>(mesh.triangles.size());
}

namespace {

/// Throws unless every component of the scale is non-zero with magnitude at most kMaxCoordinate.
void checkScale(const std::string& path, const Eigen::Vector3d& scale) {
  if ((scale.array() != 0.0).all() && scale.cwiseAbs().maxCoeff() <= geometry::range::kMaxCoordinate) return;
  std::ostringstream msg;
  msg << "mesh file " << inQuotes(path) << ": scale (" << format(scale)
      << ") must have non-zero components of magnitude at most " << geometry::range::kMaxCoordinate;
  throw std::invalid_argument(msg.str());
}

/// Throws unless `path` is a readable regular file of at most options.maxFileBytes.
void checkFile(const std::string& path, const MeshLoadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw std::invalid_argument("mesh file " + inQuotes(path) + " does not exist");
  }
  if (!fs::is_regular_file(path, ec)) {
    throw std::invalid_argument("mesh file " + inQuotes(path) + " is not a regular file");
  }
  if (!std::ifstream(path).good()) {
    throw std::invalid_argument("mesh file " + inQuotes(path) + " cannot be opened for reading");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > options.maxFileBytes) {
    throw std::invalid_argument(
        "mesh file " + inQuotes(path) + " has " + std::to_string(size) +
        " bytes, more than MeshLoadOptions::maxFileBytes = " + std::to_string(options.maxFileBytes) +
        " (a robot's or world's: CollisionGeometryOptions::meshLoad)");
  }
}

}  // namespace

TriangleMesh loadMesh(const std::string& path, const Eigen::Vector3d& scale, const MeshLoadOptions& options) {
  checkScale(path, scale);
  checkFile(path, options);
  checkXmlMeshFile(path);
  checkObjMeshFile(path);
  Assimp::Importer importer;
  // Use COLLADA coordinates as written (see the header comment); keep its unit.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::invalid_argument("mesh file " + inQuotes(path) +
                                " cannot be read by assimp: " + importer.GetErrorString() + binaryStlHint(path));
  }

  TriangleMesh mesh;
  mesh.source = path;
  Merger merger(*scene, scale, mesh);
  merger.addTree(*scene->mRootNode);
  const int total = static_cast<int>(mesh.triangles.size());
  if (total == 0) {
    throw std::invalid_argument("mesh file " + inQuotes(path) + " contains no triangles");
  }
  removeDegenerateTriangles(mesh);
  if (mesh.triangles.empty()) {
    throw std::invalid_argument("mesh file " + inQuotes(path) + ": all " + std::to_string(total) +
                                " triangles are degenerate (zero area)");
  }
  return mesh;
}

}  // namespace deepcheck::robots
