#include "probe_icosahedron.h"

#include <Eigen/Geometry>

#include <cmath>
#include <utility>

namespace deepcheck::geometry::probe {
namespace {

static_assert(kDirections == 12, "an icosahedron has twelve vertices");

Icosahedron build() {
  Icosahedron ico{};
  // Vertices (0, ±1, ±g), (±1, ±g, 0), (±g, 0, ±1), g the golden ratio: edges have length 2.
  const double g = 0.5 * (1.0 + std::sqrt(5.0));
  Eigen::Vector3d v[kDirections];
  int k = 0;
  for (const double s : {-1.0, 1.0}) {
    for (const double t : {-1.0, 1.0}) {
      v[k++] = {0.0, s, t * g};
      v[k++] = {s, t * g, 0.0};
      v[k++] = {t * g, 0.0, s};
    }
  }
  const auto adjacent = [&](int i, int j) { return std::abs((v[i] - v[j]).squaredNorm() - 4.0) < 1e-9; };
  int f = 0;
  for (int a = 0; a < kDirections; ++a) {
    for (int b = a + 1; b < kDirections; ++b) {
      for (int c = b + 1; c < kDirections; ++c) {
        if (!adjacent(a, b) || !adjacent(b, c) || !adjacent(a, c)) continue;
        int* corners = ico.face[f++];
        const bool outward = (v[b] - v[a]).cross(v[c] - v[a]).dot(v[a]) > 0.0;
        corners[0] = a;
        corners[1] = outward ? b : c;
        corners[2] = outward ? c : b;
      }
    }
  }
  // Neighbours: face h's edge (u, w) is edge (w, u) of its neighbour.
  for (int h = 0; h < kFaces; ++h) {
    for (int e = 0; e < 3; ++e) {
      const int u = ico.face[h][e], w = ico.face[h][(e + 1) % 3];
      for (int o = 0; o < kFaces; ++o)
        for (int x = 0; x < 3; ++x)
          if (ico.face[o][x] == w && ico.face[o][(x + 1) % 3] == u) ico.adj[h][e] = 4 * o + x;
    }
  }
  for (int i = 0; i < kDirections; ++i) ico.direction[i] = genericOrientation() * v[i].normalized();
  for (int i = 0; i < kDirections; ++i)
    for (int j = 0; j < kDirections; ++j)
      if ((v[i] + v[j]).squaredNorm() < 1e-18) ico.opposite[i] = j;
  return ico;
}

}  // namespace

const Icosahedron& icosahedron() {
  static const Icosahedron ico = build();
  return ico;
}

const Eigen::Matrix3d& genericOrientation() {
  static const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.4, -0.6, 0.7).normalized()).toRotationMatrix();
  return R;
}

}  // namespace deepcheck::geometry::probe

namespace deepcheck::geometry {

const Eigen::Vector3d& detail::probeDirection(int i) { return probe::icosahedron().direction[i]; }

}  // namespace deepcheck::geometry
