// The hand of hand_mesh.h: tubes swept along planar paths.

#include "hand_mesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace deepcheck::bench {

namespace {

using Eigen::Vector3d;

/// A planar path: points with the normal of their plane (constant along the path).
struct Path {
  std::vector<Vector3d> points;
  Vector3d planeNormal;
};

/// A straight segment from `a` up along `up` for `straight` metres, then an arc of `angle` radians
/// of radius `bend` curling towards `curl` (perpendicular to `up`), sampled by `steps` points.
Path fingerPath(const Vector3d& a, const Vector3d& up, const Vector3d& curl, double straight, double bend, double angle,
                int steps) {
  Path path{{}, up.cross(curl).normalized()};
  const double total = straight + bend * angle;
  for (int i = 0; i <= steps; ++i) {
    const double s = total * i / steps;
    if (s <= straight) {
      path.points.push_back(a + s * up);
    } else {
      const double t = (s - straight) / bend;
      const Vector3d center = a + straight * up + bend * curl;
      path.points.push_back(center - bend * std::cos(t) * curl + bend * std::sin(t) * up);
    }
  }
  return path;
}

/// Appends the closed tube of `radius` around `path`, `segments` vertices per ring.
void appendTube(const Path& path, double radius, int segments, robots::TriangleMesh* mesh) {
  const int base = static_cast<int>(mesh->vertices.size());
  const int rings = static_cast<int>(path.points.size());
  for (int i = 0; i < rings; ++i) {
    const Vector3d tangent = (path.points[std::min(i + 1, rings - 1)] - path.points[std::max(i - 1, 0)]).normalized();
    const Vector3d u = path.planeNormal;
    const Vector3d v = tangent.cross(u);
    for (int k = 0; k < segments; ++k) {
      const double phi = 2.0 * M_PI * k / segments;
      mesh->vertices.push_back(path.points[i] + radius * (std::cos(phi) * u + std::sin(phi) * v));
    }
  }
  auto ring = [&](int i, int k) { return base + i * segments + (k % segments); };
  for (int i = 0; i + 1 < rings; ++i) {
    for (int k = 0; k < segments; ++k) {
      mesh->triangles.push_back({ring(i, k), ring(i, k + 1), ring(i + 1, k + 1)});
      mesh->triangles.push_back({ring(i, k), ring(i + 1, k + 1), ring(i + 1, k)});
    }
  }
  // Cone caps, their apexes half a radius beyond the ends.
  const Vector3d startOut = (path.points[0] - path.points[1]).normalized();
  const Vector3d endOut = (path.points[rings - 1] - path.points[rings - 2]).normalized();
  mesh->vertices.push_back(path.points[0] + 0.5 * radius * startOut);
  const int startApex = static_cast<int>(mesh->vertices.size()) - 1;
  mesh->vertices.push_back(path.points[rings - 1] + 0.5 * radius * endOut);
  const int endApex = startApex + 1;
  for (int k = 0; k < segments; ++k) {
    mesh->triangles.push_back({startApex, ring(0, k + 1), ring(0, k)});
    mesh->triangles.push_back({endApex, ring(rings - 1, k), ring(rings - 1, k + 1)});
  }
}

/// Segments per ring and rings for a tube of `length` and `radius` in about `triangles`
/// triangles, its quads about square.
void tubeResolution(double length, double radius, int triangles, int* segments, int* steps) {
  // triangles ~ 2 * segments * steps, steps ~ segments * length / (2 pi radius).
  const double aspect = length / (2.0 * M_PI * radius);
  *segments = std::max(8, static_cast<int>(std::sqrt(triangles / (2.0 * aspect))));
  *steps = std::max(2, static_cast<int>(triangles / (2.0 * *segments)));
}

/// The palm: a straight tube along x, radius 2.5 cm, in about `perTube` triangles.
void appendPalm(int perTube, robots::TriangleMesh* mesh) {
  int segments = 0;
  int steps = 0;
  tubeResolution(0.09, 0.025, perTube, &segments, &steps);
  appendTube(fingerPath({-0.045, 0, 0}, Vector3d::UnitX(), Vector3d::UnitY(), 0.09, 0.01, 0.0, steps), 0.025, segments,
             mesh);
}

}  // namespace

robots::TriangleMesh combMesh(int triangles) {
  robots::TriangleMesh mesh;
  mesh.source = "comb";
  constexpr int kFingers = 8;
  const int perTube = std::max(100, triangles / (kFingers + 1));
  appendPalm(perTube, &mesh);
  for (int f = 0; f < kFingers; ++f) {
    const Vector3d root(-0.042 + 0.012 * f, 0.0, 0.01);
    const double straight = 0.04 + 0.008 * (f % 3);
    int segments = 0;
    int steps = 0;
    tubeResolution(straight + 0.02 * 3.5, 0.005, perTube, &segments, &steps);
    appendTube(fingerPath(root, Vector3d::UnitZ(), Vector3d::UnitY(), straight, 0.02, 3.5, steps), 0.005, segments,
               &mesh);
  }
  return mesh;
}

robots::TriangleMesh handMesh(int triangles) {
  robots::TriangleMesh mesh;
  mesh.source = "hand";
  const int perTube = std::max(100, triangles / 5);
  int segments = 0;
  int steps = 0;
  appendPalm(perTube, &mesh);
  // Four fingers, radius 8 mm, rising from inside the palm and curling by 150 degrees.
  for (int f = 0; f < 4; ++f) {
    const Vector3d root(-0.036 + 0.024 * f, 0.0, 0.01);
    const double straight = 0.05 + 0.006 * (f % 2);
    tubeResolution(straight + 0.025 * 2.6, 0.008, perTube, &segments, &steps);
    appendTube(fingerPath(root, Vector3d::UnitZ(), Vector3d::UnitY(), straight, 0.025, 2.6, steps), 0.008, segments,
               &mesh);
  }
  return mesh;
}

}  // namespace deepcheck::bench
