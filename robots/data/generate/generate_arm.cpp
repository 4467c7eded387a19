// Writes the collision meshes of the bundled arm, deepcheck_arm (robots/data/deepcheck_arm), as
// binary STL files.
//
//   deepcheck_generate_arm OUTPUT_DIR      (OUTPUT_DIR is usually robots/data/deepcheck_arm/meshes)
//
// Self-contained (standard library only) so that a fresh machine needs nothing but a C++ compiler.
// The meshes are built from three kinds of closed, outward-facing triangle surfaces:
//   lathe     a surface of revolution about z from a stepped (r, z) profile: motor housings,
//             collars, hubs (non-convex where the radius steps);
//   extrusion a simple polygon (convex or not: U-shaped forks, L-shaped brackets and fingers, a
//             T-shaped palm) extruded between two parallel planes;
// and each link's mesh is the union of a few such closed parts that touch (along a face, a line
// or not at all) but never interpenetrate, so that the mesh volume, summed over the parts by the
// divergence theorem, is the volume of the link; every part is closed and outward-facing.
//
// Frames. Every link frame is the frame of the joint that moves it, and at the zero configuration
// all link frames are parallel to the base frame (z up): the arm stands straight up. Roll links
// (1, 3, 5, 7) turn about their z axis and carry at their top a U-shaped fork that holds the next
// (pitch) joint, whose axis is y; pitch links (2, 4, 6) have a hub along y that sits in that fork
// and a housing up to the next roll joint. The joint offsets along z are those of the URDF
// (deepcheck_arm.urdf), taken from the KUKA LBR iiwa 7 R800's published link lengths.
// Units: metres.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Segments around the axis of every lathe part: 24 keeps each link to a few hundred triangles
/// while the polygon stays within r * (1 - cos(pi / 24)) = 0.86 % of r of the true circle.
constexpr int kSegments = 24;

struct Vec3 {
  double x, y, z;
};
Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;

  void append(const Mesh& other) {
    const int base = static_cast<int>(vertices.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
};

/// A proper rotation (columns are the images of x, y, z) followed by a translation.
struct Transform {
  std::array<Vec3, 3> columns{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  Vec3 translation{0, 0, 0};
  Vec3 apply(const Vec3& p) const {
    return {columns[0].x * p.x + columns[1].x * p.y + columns[2].x * p.z + translation.x,
            columns[0].y * p.x + columns[1].y * p.y + columns[2].y * p.z + translation.y,
            columns[0].z * p.x + columns[1].z * p.y + columns[2].z * p.z + translation.z};
  }
};

/// Maps the z axis onto the y axis (a rotation of -90 degrees about x), then translates.
Transform zToY(double x, double y, double z) {
  Transform t;
  t.columns = {Vec3{1, 0, 0}, Vec3{0, 0, -1}, Vec3{0, 1, 0}};
  t.translation = {x, y, z};
  return t;
}
/// Maps (a, b, c) to (y, z, x): a polygon drawn in the y-z plane, extruded along x.
Transform yzPlane() {
  Transform t;
  t.columns = {Vec3{0, 1, 0}, Vec3{0, 0, 1}, Vec3{1, 0, 0}};
  return t;
}
/// Maps (a, b, c) to (x, z, -y): a polygon drawn in the x-z plane, extruded along y.
Transform xzPlane() {
  Transform t;
  t.columns = {Vec3{1, 0, 0}, Vec3{0, 0, 1}, Vec3{0, -1, 0}};
  return t;
}

Mesh transformed(Mesh m, const Transform& t) {
  for (Vec3& v : m.vertices) v = t.apply(v);
  return m;
}

/// Surface of revolution about z. `profile` lists (r, z) from the bottom pole (r = 0) to the top
/// pole (r = 0), going outward and up: the surface faces outward.
Mesh lathe(const std::vector<std::pair<double, double>>& profile) {
  Mesh m;
  std::vector<std::vector<int>> ring(profile.size());
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const auto [r, z] = profile[i];
    if (r == 0.0) {
      ring[i].assign(kSegments, static_cast<int>(m.vertices.size()));
      m.vertices.push_back({0.0, 0.0, z});
      continue;
    }
    for (int j = 0; j < kSegments; ++j) {
      const double a = 2.0 * kPi * j / kSegments;
      ring[i].push_back(static_cast<int>(m.vertices.size()));
      m.vertices.push_back({r * std::cos(a), r * std::sin(a), z});
    }
  }
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const bool lowerPole = profile[i].first == 0.0;
    const bool upperPole = profile[i + 1].first == 0.0;
    for (int j = 0; j < kSegments; ++j) {
      const int k = (j + 1) % kSegments;
      const int a0 = ring[i][j], a1 = ring[i][k], b0 = ring[i + 1][j], b1 = ring[i + 1][k];
      if (!lowerPole) m.triangles.push_back({a0, a1, b1});
      if (!upperPole) m.triangles.push_back({a0, b1, b0});
    }
  }
  return m;
}

/// Twice the signed area of triangle (a, b, c) in the plane.
double orient(const std::pair<double, double>& a, const std::pair<double, double>& b,
              const std::pair<double, double>& c) {
  return (b.first - a.first) * (c.second - a.second) - (b.second - a.second) * (c.first - a.first);
}

/// Ear clipping of a simple counter-clockwise polygon (no three consecutive collinear corners).
std::vector<std::array<int, 3>> triangulate(const std::vector<std::pair<double, double>>& poly) {
  std::vector<int> left(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) left[i] = static_cast<int>(i);
  std::vector<std::array<int, 3>> out;
  while (left.size() > 3) {
    const int n = static_cast<int>(left.size());
    bool clipped = false;
    for (int i = 0; i < n && !clipped; ++i) {
      const int p = left[(i + n - 1) % n], c = left[i], q = left[(i + 1) % n];
      if (orient(poly[p], poly[c], poly[q]) <= 0.0) continue;  // reflex corner
      bool empty = true;
      for (int o : left) {
        if (o == p || o == c || o == q) continue;
        if (orient(poly[p], poly[c], poly[o]) >= 0.0 && orient(poly[c], poly[q], poly[o]) >= 0.0 &&
            orient(poly[q], poly[p], poly[o]) >= 0.0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({p, c, q});
      left.erase(left.begin() + i);
      clipped = true;
    }
    if (!clipped) {
      std::fprintf(stderr, "generate_arm: polygon is not simple and counter-clockwise\n");
      std::exit(1);
    }
  }
  out.push_back({left[0], left[1], left[2]});
  return out;
}

/// A simple counter-clockwise polygon in the (a, b) plane extruded over c in [-depth/2, depth/2].
Mesh extrusion(const std::vector<std::pair<double, double>>& poly, double depth) {
  Mesh m;
  const int n = static_cast<int>(poly.size());
  for (const auto& [a, b] : poly) m.vertices.push_back({a, b, -depth / 2});
  for (const auto& [a, b] : poly) m.vertices.push_back({a, b, depth / 2});
  for (const auto& t : triangulate(poly)) {
    m.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});  // top cap, facing +c
    m.triangles.push_back({t[0], t[2], t[1]});              // bottom cap, facing -c
  }
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    m.triangles.push_back({i, k, k + n});
    m.triangles.push_back({i, k + n, i + n});
  }
  return m;
}

/// A U-shaped fork in the y-z plane: outer half-width `outer`, inner half-width `inner`, from z0
/// to z1, its bottom bar from z0 to zBar; extruded over x in [-halfDepth, halfDepth].
Mesh fork(double outer, double inner, double z0, double zBar, double z1, double halfDepth) {
  const std::vector<std::pair<double, double>> u = {{-outer, z0},  {outer, z0},    {outer, z1},  {inner, z1},
                                                    {inner, zBar}, {-inner, zBar}, {-inner, z1}, {-outer, z1}};
  return transformed(extrusion(u, 2 * halfDepth), yzPlane());
}

/// A roll link: a stepped housing (collar, then body) and a fork for the next pitch joint,
/// whose axis (y) is at height `jointZ`.
Mesh rollLink(double collarR, double bodyR, double forkOuter, double forkInner, double forkDepth, double jointZ) {
  Mesh m = lathe({{0, 0.005}, {collarR, 0.005}, {collarR, 0.030}, {bodyR, 0.030}, {bodyR, 0.100}, {0, 0.100}});
  m.append(fork(forkOuter, forkInner, 0.100, 0.115, jointZ + 0.060, forkDepth));
  return m;
}

/// A pitch link: a hub along y (radius hubR, half-length hubHalf) at the origin, and a housing
/// standing on it (from z = hubR, where it touches the hub along a line) up to the next roll
/// joint at height `nextZ`, with a collar at its top when collarR > tubeR.
Mesh pitchLink(double hubR, double hubHalf, double tubeR, double collarR, double nextZ) {
  Mesh m = transformed(lathe({{0, -hubHalf}, {hubR, -hubHalf}, {hubR, hubHalf}, {0, hubHalf}}), zToY(0, 0, 0));
  if (collarR > tubeR) {
    m.append(lathe({{0, hubR},
                    {tubeR, hubR},
                    {tubeR, nextZ - 0.040},
                    {collarR, nextZ - 0.040},
                    {collarR, nextZ - 0.005},
                    {0, nextZ - 0.005}}));
  } else {
    m.append(lathe({{0, hubR}, {tubeR, hubR}, {tubeR, nextZ - 0.005}, {0, nextZ - 0.005}}));
  }
  return m;
}

void putLe32(std::FILE* f, std::uint32_t v) {
  const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                              static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 24)};
  std::fwrite(b, 1, 4, f);
}
void putFloat(std::FILE* f, double v) {
  const float x = static_cast<float>(v);
  std::uint32_t bits;
  static_assert(sizeof bits == sizeof x, "32-bit float");
  std::memcpy(&bits, &x, sizeof bits);
  putLe32(f, bits);
}

/// Exits unless every directed edge is matched by exactly one opposite edge (closed and
/// consistently wound) and the enclosed volume is positive (facing outward).
void checkClosedOutward(const std::string& name, const Mesh& m) {
  std::map<std::pair<int, int>, int> edges;
  double volume6 = 0.0;
  for (const auto& t : m.triangles) {
    for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Vec3 n = cross(b, c);
    volume6 += a.x * n.x + a.y * n.y + a.z * n.z;
  }
  for (const auto& [edge, count] : edges) {
    const auto opposite = edges.find({edge.second, edge.first});
    if (count != 1 || opposite == edges.end() || opposite->second != 1) {
      std::fprintf(stderr, "generate_arm: %s is not closed at edge (%d, %d)\n", name.c_str(), edge.first, edge.second);
      std::exit(1);
    }
  }
  if (!(volume6 > 0.0)) {
    std::fprintf(stderr, "generate_arm: %s faces inward (volume %g)\n", name.c_str(), volume6 / 6);
    std::exit(1);
  }
}

/// Binary STL (little-endian, as the format requires), facet normals from the winding.
void writeStl(const std::string& path, const std::string& name, const Mesh& m) {
  checkClosedOutward(name, m);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    std::fprintf(stderr, "generate_arm: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  char header[80] = {};
  std::snprintf(header, sizeof header, "deepcheck_arm %s (robots/data/generate/generate_arm.cpp)", name.c_str());
  std::fwrite(header, 1, sizeof header, f);
  putLe32(f, static_cast<std::uint32_t>(m.triangles.size()));
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    Vec3 n = cross(b - a, c - a);
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n = {n.x / len, n.y / len, n.z / len};
    for (double v : {n.x, n.y, n.z, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}) putFloat(f, v);
    const unsigned char attribute[2] = {0, 0};
    std::fwrite(attribute, 1, 2, f);
  }
  if (std::fclose(f) != 0) {
    std::fprintf(stderr, "generate_arm: error writing %s\n", path.c_str());
    std::exit(1);
  }
  std::printf("%-18s %4zu triangles\n", (name + ".stl").c_str(), m.triangles.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: deepcheck_generate_arm OUTPUT_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  auto write = [&](const std::string& name, const Mesh& m) { writeStl(dir + "/" + name + ".stl", name, m); };

  // Base: a foot flange and a neck up to joint 1 (z = 0.15), and an L-shaped cable bracket at
  // the back (-x), 1 mm clear of the neck.
  Mesh base = lathe({{0, 0.0}, {0.120, 0.0}, {0.120, 0.025}, {0.080, 0.025}, {0.080, 0.145}, {0, 0.145}});
  base.append(transformed(
      extrusion({{-0.150, 0.025}, {-0.081, 0.025}, {-0.081, 0.040}, {-0.135, 0.040}, {-0.135, 0.100}, {-0.150, 0.100}},
                0.060),
      xzPlane()));
  write("base", base);

  // Joint offsets (URDF): j2 0.19 above j1, j3 0.21 above j2, j4 0.19, j5 0.21, j6 0.19, j7 0.081.
  write("link1", rollLink(0.080, 0.070, 0.095, 0.070, 0.060, 0.19));
  write("link2", pitchLink(0.060, 0.065, 0.060, 0.070, 0.21));
  write("link3", rollLink(0.070, 0.065, 0.090, 0.065, 0.055, 0.19));
  write("link4", pitchLink(0.055, 0.060, 0.055, 0.065, 0.21));
  write("link5", rollLink(0.065, 0.060, 0.085, 0.060, 0.050, 0.19));
  write("link6", pitchLink(0.050, 0.055, 0.050, 0.050, 0.081));
  // Link 7: a stepped drive housing up to the flange (0.045 above joint 7).
  write("link7", lathe({{0, 0.005}, {0.050, 0.005}, {0.050, 0.020}, {0.040, 0.020}, {0.040, 0.045}, {0, 0.045}}));

  // Palm, in the hand frame (= flange frame): a mounting disc and a T-shaped body, 7 cm tall,
  // 18 cm wide along y, 7 cm deep along x.
  Mesh hand = lathe({{0, 0.0}, {0.040, 0.0}, {0.040, 0.012}, {0, 0.012}});
  hand.append(transformed(extrusion({{-0.030, 0.012},
                                     {0.030, 0.012},
                                     {0.030, 0.030},
                                     {0.090, 0.030},
                                     {0.090, 0.070},
                                     {-0.090, 0.070},
                                     {-0.090, 0.030},
                                     {-0.030, 0.030}},
                                    0.070),
                          yzPlane()));
  write("hand", hand);

  // Finger (the left one; the right one is the same mesh turned half a turn about z): an L in
  // the y-z plane, a sliding block 3 cm long and an upright 6.5 cm tall on its inner (y = 0)
  // side, 2 cm thick along x.
  write("finger",
        transformed(
            extrusion({{0.0, 0.0}, {0.030, 0.0}, {0.030, 0.012}, {0.012, 0.012}, {0.012, 0.065}, {0.0, 0.065}}, 0.020),
            yzPlane()));
  return 0;
}
