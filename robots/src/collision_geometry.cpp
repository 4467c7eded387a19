#include "deepcheck/robots/collision_geometry.h"

#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/mesh_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace deepcheck::robots {
namespace {

using PolytopeList = std::vector<std::shared_ptr<const geometry::ConvexPolytope>>;

/// Meshes already turned into pieces during one call, keyed by (path, scale).
using MeshCache = std::map<std::tuple<std::string, double, double, double>, PolytopeList>;

std::string describe(const RobotModel& model, int link, int collision) {
  return "URDF '" + model.source() + "', link '" + model.link(link).name + "', collision " + std::to_string(collision);
}

const PolytopeList& meshPieces(const RobotModel& model, int link, int collision, const Geometry& g,
                               const CollisionGeometryOptions& options, MeshCache& cache) {
  const auto key = std::make_tuple(g.meshPath, g.meshScale.x(), g.meshScale.y(), g.meshScale.z());
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  PolytopeList pieces;
  try {
    std::vector<geometry::ConvexPolytope> polytopes =
        meshPolytopes(loadMesh(g.meshPath, g.meshScale, options.meshLoad), options);
    for (geometry::ConvexPolytope& p : polytopes) {
      pieces.push_back(std::make_shared<const geometry::ConvexPolytope>(std::move(p)));
    }
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(describe(model, link, collision) + ": " + e.what());
  }
  return cache.emplace(key, std::move(pieces)).first->second;
}

std::vector<CollisionPiece> piecesOfLink(const RobotModel& model, int link, const CollisionGeometryOptions& options,
                                         MeshCache& cache) {
  if (!(options.cylinderMaxDeviation > 0.0)) {
    throw std::invalid_argument("cylinderMaxDeviation must be positive, is " +
                                formatNumber(options.cylinderMaxDeviation));
  }
  std::vector<CollisionPiece> out;
  const Link& L = model.link(link);
  for (int c = 0; c < static_cast<int>(L.collisions.size()); ++c) {
    const CollisionElement& element = L.collisions[c];
    const Geometry& g = element.geometry;
    const std::string prefix = "link " + L.name + " collision " + std::to_string(c);
    if (g.type != GeometryType::Mesh) {
      CollisionPiece piece = primitivePiece(g, options, prefix);
      piece.X_LP = element.X_LG;
      out.push_back(std::move(piece));
      continue;
    }
    const PolytopeList& pieces = meshPieces(model, link, c, g, options, cache);
    const std::string file = std::filesystem::path(g.meshPath).filename().string();
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      CollisionPiece piece;
      piece.X_LP = element.X_LG;
      piece.core = pieces[i];
      piece.origin = prefix + " mesh " + file + " piece " + std::to_string(i);
      out.push_back(std::move(piece));
    }
  }
  return out;
}

}  // namespace

CollisionPiece primitivePiece(const Geometry& g, const CollisionGeometryOptions& options, const std::string& what) {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  CollisionPiece piece;
  switch (g.type) {
    case GeometryType::Box:
      if (!positive(g.boxSize.x()) || !positive(g.boxSize.y()) || !positive(g.boxSize.z())) {
        std::ostringstream msg;
        msg << what << ": box size (" << g.boxSize.transpose() << ") must be positive and finite";
        throw std::invalid_argument(msg.str());
      }
      piece.core = std::make_shared<const geometry::ConvexPolytope>(geometry::ConvexPolytope::box(g.boxSize));
      piece.origin = what + " box";
      return piece;
    case GeometryType::Sphere:
      if (!positive(g.radius)) {
        throw std::invalid_argument(what + ": sphere radius " + formatNumber(g.radius) +
                                    " must be positive and finite");
      }
      piece.origin = what + " sphere";
      piece.core = std::make_shared<const geometry::ConvexPolytope>(
          geometry::ConvexPolytope::fromPoints({Eigen::Vector3d::Zero()}, piece.origin));
      piece.radius = g.radius;
      return piece;
    case GeometryType::Cylinder:
      if (!positive(g.radius) || !positive(g.length)) {
        throw std::invalid_argument(what + ": cylinder radius " + formatNumber(g.radius) + " and length " +
                                    formatNumber(g.length) + " must be positive and finite");
      }
      piece.core = std::make_shared<const geometry::ConvexPolytope>(
          cylinderPrism(g.radius, g.length, options.cylinderMaxDeviation));
      piece.origin = what + " cylinder (" + std::to_string(cylinderSides(g.radius, options.cylinderMaxDeviation)) +
                     "-sided prism)";
      return piece;
    case GeometryType::Mesh:
      break;
  }
  throw std::invalid_argument(what + ": a mesh is not a primitive");
}

std::vector<geometry::ConvexPolytope> meshPolytopes(const TriangleMesh& mesh, const CollisionGeometryOptions& options) {
  if (mesh.empty()) throw std::invalid_argument("the mesh has no triangle");
  std::vector<geometry::ConvexPolytope> polytopes =
      options.decomposer ? options.decomposer(mesh) : convexHullDecomposer(mesh);
  if (polytopes.empty()) throw std::invalid_argument("the mesh decomposer returned no piece");
  return polytopes;
}

std::vector<geometry::ConvexPolytope> convexHullDecomposer(const TriangleMesh& mesh) {
  std::vector<geometry::ConvexPolytope> out;
  out.push_back(geometry::ConvexPolytope::fromPoints(mesh.vertices, mesh.source));
  return out;
}

int cylinderSides(double radius, double maxDeviation) {
  if (!(radius > 0.0) || !(maxDeviation > 0.0)) {
    std::ostringstream msg;
    msg << "cylinder radius " << radius << " and maximum deviation " << maxDeviation << " must be positive";
    throw std::invalid_argument(msg.str());
  }
  // r / cos(pi / N) - r <= d  <=>  pi / N <= acos(r / (r + d)).
  const double half = std::acos(radius / (radius + maxDeviation));
  const double n = half > 0.0 ? std::ceil(M_PI / half) : double(tol::kCylinderMaxSides);
  return static_cast<int>(std::clamp(n, double(tol::kCylinderMinSides), double(tol::kCylinderMaxSides)));
}

geometry::ConvexPolytope cylinderPrism(double radius, double length, double maxDeviation) {
  if (!(length > 0.0) || !std::isfinite(length) || !std::isfinite(radius)) {
    std::ostringstream msg;
    msg << "cylinder length " << length << " and radius " << radius << " must be positive and finite";
    throw std::invalid_argument(msg.str());
  }
  const int sides = cylinderSides(radius, maxDeviation);
  const double corner = radius / std::cos(M_PI / sides);
  std::vector<Eigen::Vector3d> points;
  points.reserve(2 * sides);
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * M_PI * k / sides;
    for (double z : {-0.5 * length, 0.5 * length}) {
      points.emplace_back(corner * std::cos(angle), corner * std::sin(angle), z);
    }
  }
  return geometry::ConvexPolytope::fromPoints(points, "cylinder");
}

std::vector<CollisionPiece> linkCollisionPieces(const RobotModel& model, int link,
                                                const CollisionGeometryOptions& options) {
  if (link < 0 || link >= model.numLinks()) {
    throw std::invalid_argument("robot '" + model.name() + "': link index " + std::to_string(link) + " out of range");
  }
  MeshCache cache;
  return piecesOfLink(model, link, options, cache);
}

std::vector<std::vector<CollisionPiece>> collisionPieces(const RobotModel& model,
                                                         const CollisionGeometryOptions& options) {
  MeshCache cache;
  std::vector<std::vector<CollisionPiece>> out;
  out.reserve(model.numLinks());
  for (int l = 0; l < model.numLinks(); ++l) out.push_back(piecesOfLink(model, l, options, cache));
  return out;
}

}  // namespace deepcheck::robots
