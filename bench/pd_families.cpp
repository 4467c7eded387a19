// Generated families of the penetration-depth benchmark (see pd_families.h).

#include "pd_families.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace deepcheck::bench {

using Eigen::Quaterniond;
using Eigen::Vector3d;
using geometry::ConvexPolytope;

Eigen::Isometry3d Pose::iso() const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = t;
  return X;
}

int Family::addShape(std::vector<Eigen::Vector3d> pts, const std::string& shapeName) {
  shapes.push_back(ConvexPolytope::fromPoints(pts, shapeName));
  points.push_back(std::move(pts));
  return static_cast<int>(shapes.size()) - 1;
}

double Family::pairScale(const Query& q) const {
  return std::max(shapes[q.a].boundingRadius(), shapes[q.b].boundingRadius());
}

const geometry::ExactResult& exactOf(const Family& family, Query& q) {
  if (!q.exact) {
    const auto t0 = std::chrono::steady_clock::now();
    q.exact = geometry::exactSignedDistance(family.shapes[q.a], q.X_WA, family.shapes[q.b], q.X_WB);
    const auto t1 = std::chrono::steady_clock::now();
    q.exactMicros = std::chrono::duration<double, std::micro>(t1 - t0).count();
  }
  return *q.exact;
}

std::vector<std::string> familyNames() {
  return {"verts_8",    "verts_30",    "verts_100", "verts_300",  "verts_1000", "verts_3000", "aspect_10",
          "aspect_100", "aspect_1000", "far_1e4",   "scale_1e-3", "scale_1e3",  "touching",   "deep",
          "separated",  "boxes",       "polygons",  "motion",     "robots"};
}

std::vector<Eigen::Vector3d> readStlVertices(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open STL file " + path);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Eigen::Vector3d> pts;
  // Binary STL: 80-byte header, uint32 triangle count, 50 bytes per triangle (normal, three
  // vertices as float32, 2 attribute bytes). Recognized by its exact size, since binary files
  // may begin with "solid" too.
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50ull * count) {
      for (std::uint32_t i = 0; i < count; ++i) {
        const char* tri = bytes.data() + 84 + 50ull * i + 12;
        for (int k = 0; k < 3; ++k) {
          float xyz[3];
          std::memcpy(xyz, tri + 12 * k, 12);
          pts.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
      }
      return pts;
    }
  }
  // ASCII STL: every "vertex x y z" line.
  std::istringstream text(bytes);
  std::string word;
  while (text >> word) {
    if (word == "vertex") {
      Eigen::Vector3d p;
      text >> p.x() >> p.y() >> p.z();
      if (!text) throw std::runtime_error("bad vertex line in STL file " + path);
      pts.push_back(p);
    }
  }
  if (pts.empty()) throw std::runtime_error("no vertices in STL file " + path);
  return pts;
}

namespace {

/// Stable seed from a family name (FNV-1a), so each family is the same however it is run.
std::uint32_t seedOf(const std::string& name) {
  std::uint32_t h = 2166136261u;
  for (char c : name) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return h;
}

class Generator {
 public:
  explicit Generator(const std::string& name) : rng_(seedOf(name)) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  Vector3d unit() {
    std::normal_distribution<double> g(0.0, 1.0);
    Vector3d v;
    do {
      v = Vector3d(g(rng_), g(rng_), g(rng_));
    } while (v.norm() < 1e-6);
    return v.normalized();
  }

  Quaterniond rotation() {
    std::normal_distribution<double> g(0.0, 1.0);
    Quaterniond q(g(rng_), g(rng_), g(rng_), g(rng_));
    q.normalize();
    return q;
  }

  /// n random points on an ellipsoid surface with semi-axes `semi` (all are hull vertices).
  std::vector<Vector3d> ellipsoid(int n, const Vector3d& semi) {
    std::vector<Vector3d> pts;
    pts.reserve(n);
    for (int i = 0; i < n; ++i) pts.push_back(unit().cwiseProduct(semi));
    return pts;
  }

  /// Semi-axes of a "round" random hull of size ~scale: (1, [0.5, 1], [0.5, 1]) * scale.
  Vector3d roundSemi(double scale) { return scale * Vector3d(1.0, uniform(0.5, 1.0), uniform(0.5, 1.0)); }

 private:
  std::mt19937 rng_;
};

std::vector<Vector3d> boxCorners(const Vector3d& h) {
  std::vector<Vector3d> pts;
  for (int i = 0; i < 8; ++i)
    pts.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  return pts;
}

/// Translation of B that puts B's centroid at the point of A that is the fraction s of the way
/// from A's centroid to A's vertex v (inside A for s in [0, 1], so the pair overlaps).
Vector3d insidePlacement(const ConvexPolytope& A, const Pose& poseA, int v, double s, const ConvexPolytope& B,
                         const Quaterniond& qB) {
  const Vector3d target_A = A.center() + s * (A.vertex(v) - A.center());
  const Vector3d target_W = poseA.q * target_A + poseA.t;
  return target_W - qB * B.center();
}

/// Adds a query of shapes (a, b), A at poseA and B with orientation qB, B's centroid placed
/// inside A at fraction s in [smin, smax) towards a random vertex.
void addInsideQuery(Family& f, Generator& g, int a, int b, const Pose& poseA, double smin, double smax) {
  Query q;
  q.a = a;
  q.b = b;
  q.poseA = poseA;
  q.poseB.q = g.rotation();
  const ConvexPolytope& A = f.shapes[a];
  q.poseB.t = insidePlacement(A, poseA, g.index(A.numVertices()), g.uniform(smin, smax), f.shapes[b], q.poseB.q);
  f.queries.push_back(q);
}

/// The priming pose for a warm start: B moved by 1 % of L and turned by 0.01 rad.
Pose nearbyPose(Generator& g, const Pose& p, double L) {
  Pose n = p;
  const Quaterniond turn(Eigen::AngleAxisd(0.01, g.unit()));
  n.q = (turn * p.q).normalized();
  n.t = p.t + 0.01 * L * g.unit();
  return n;
}

/// Random pairs of ellipsoid hulls: `vertices` each, A of size `scale`, B of 0.5..1 times that,
/// `semi` giving the semi-axes; B's centroid inside A at fraction [smin, smax).
void addEllipsoidPairs(Family& f, Generator& g, int pairs, int vertices, double scale, double smin, double smax,
                       const Vector3d& base, bool elongated, double aspect) {
  for (int i = 0; i < pairs; ++i) {
    auto semi = [&](double s) -> Vector3d {
      if (!elongated) return g.roundSemi(s);
      // Between a needle (1, 1/aspect, 1/aspect) and a disc (1, 1, 1/aspect).
      return s * Vector3d(1.0, std::pow(aspect, -g.uniform(0.0, 1.0)), 1.0 / aspect);
    };
    const int a = f.addShape(g.ellipsoid(vertices, semi(scale)));
    f.addShape(g.ellipsoid(vertices, semi(scale * g.uniform(0.5, 1.0))));
    Pose poseA;
    poseA.q = g.rotation();
    poseA.t = base + scale * 0.1 * g.unit();
    addInsideQuery(f, g, a, a + 1, poseA, smin, smax);
  }
}

/// Moves B of query q along the exact answer's normal so that the signed distance becomes
/// about `target` (negative: overlap). Translating B by -sd * n makes the pair touch.
void moveToSignedDistance(Family& f, Query& q, double target) {
  q.X_WA = q.poseA.iso();
  q.X_WB = q.poseB.iso();
  q.exact.reset();
  const geometry::ExactResult e = exactOf(f, q);
  q.poseB.t += (target - e.distance) * e.normal;
  q.exact.reset();
}

Family ellipsoidFamily(const std::string& name, int pairs, int vertices) {
  Family f;
  f.name = name;
  f.nominalVertices = vertices;
  f.description = "random ellipsoid hulls, " + std::to_string(vertices) + " vertices each, overlapping";
  Generator g(name);
  addEllipsoidPairs(f, g, pairs, vertices, 1.0, 0.0, 1.0, Vector3d::Zero(), false, 1.0);
  return f;
}

Family boxFamily(int pairs) {
  Family f;
  f.name = "boxes";
  f.description = "boxes: random, parallel faces, and stacked with coplanar side faces";
  Generator g(f.name);
  // The 24 rotations of a cube, as compositions of quarter turns about the axes.
  std::vector<Quaterniond> cube;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        const Quaterniond r = Quaterniond(Eigen::AngleAxisd(i * M_PI / 2, Vector3d::UnitX())) *
                              Quaterniond(Eigen::AngleAxisd(j * M_PI / 2, Vector3d::UnitY())) *
                              Quaterniond(Eigen::AngleAxisd(k * M_PI / 2, Vector3d::UnitZ()));
        cube.push_back(r.normalized());
      }
  for (int i = 0; i < pairs; ++i) {
    const Vector3d hA(g.uniform(0.2, 1.0), g.uniform(0.2, 1.0), g.uniform(0.2, 1.0));
    const Vector3d hB(g.uniform(0.2, 1.0), g.uniform(0.2, 1.0), g.uniform(0.2, 1.0));
    const int a = f.addShape(boxCorners(hA));
    f.addShape(boxCorners(hB));
    Pose poseA;
    poseA.q = g.rotation();
    poseA.t = 0.1 * g.unit();
    const int kind = i % 3;
    if (kind == 0) {
      addInsideQuery(f, g, a, a + 1, poseA, 0.0, 1.0);
      continue;
    }
    Query q;
    q.a = a;
    q.b = a + 1;
    q.poseA = poseA;
    Vector3d offset_A;
    if (kind == 1) {
      // Parallel faces: B turned by a cube symmetry relative to A, centre inside A.
      q.poseB.q = (poseA.q * cube[g.index(static_cast<int>(cube.size()))]).normalized();
      offset_A = Vector3d(g.uniform(-1, 1) * hA.x(), g.uniform(-1, 1) * hA.y(), g.uniform(-1, 1) * hA.z());
    } else {
      // Stacked: same orientation, B on A's top face sunk by up to 30 % of the thinner box, one
      // pair of side faces coplanar (x), the other offset at random (y).
      q.poseB.q = poseA.q;
      const double sink = g.uniform(0.0, 0.3) * std::min(hA.z(), hB.z());
      offset_A = Vector3d(hA.x() - hB.x(), g.uniform(-1, 1) * hA.y(), hA.z() + hB.z() - sink);
    }
    q.poseB.t = poseA.t + poseA.q * offset_A;
    f.queries.push_back(q);
  }
  return f;
}

Family polygonFamily(int pairs) {
  Family f;
  f.name = "polygons";
  f.description = "flat convex polygons (24-gon ellipses) against hulls and against polygons";
  Generator g(f.name);
  auto polygon = [&]() {
    const double b = g.uniform(0.3, 1.0);
    std::vector<Vector3d> pts;
    for (int k = 0; k < 24; ++k) {
      const double t = 2 * M_PI * (k + g.uniform(0.0, 0.5)) / 24;
      pts.emplace_back(std::cos(t), b * std::sin(t), 0.0);
    }
    return pts;
  };
  for (int i = 0; i < pairs; ++i) {
    const int a = f.addShape(polygon());
    const int kind = i % 10;
    if (kind < 5) {
      f.addShape(g.ellipsoid(100, g.roundSemi(g.uniform(0.5, 1.0))));
    } else {
      f.addShape(polygon());
    }
    Pose poseA;
    poseA.q = g.rotation();
    poseA.t = 0.1 * g.unit();
    if (kind == 9) {
      // Coplanar polygons: the Minkowski difference is flat and the depth is 0.
      Query q;
      q.a = a;
      q.b = a + 1;
      q.poseA = poseA;
      q.poseB.q = (poseA.q * Quaterniond(Eigen::AngleAxisd(g.uniform(0, 2 * M_PI), Vector3d::UnitZ()))).normalized();
      q.poseB.t = poseA.t + poseA.q * Vector3d(g.uniform(-0.5, 0.5), g.uniform(-0.3, 0.3), 0.0);
      f.queries.push_back(q);
    } else {
      addInsideQuery(f, g, a, a + 1, poseA, 0.0, 1.0);
    }
  }
  return f;
}

Family motionFamily(int steps) {
  Family f;
  f.name = "motion";
  f.sequence = true;
  f.description = "one pair of 100-vertex hulls per trajectory, B passing through A in small steps";
  Generator g(f.name);
  // 500 steps per trajectory whatever the total, so that a step is the same in quick runs.
  const int perTrajectory = 500;
  const int trajectories = std::max(1, steps / perTrajectory);
  for (int k = 0; k < trajectories; ++k) {
    const int a = f.addShape(g.ellipsoid(100, g.roundSemi(1.0)));
    f.addShape(g.ellipsoid(100, g.roundSemi(g.uniform(0.5, 1.0))));
    const ConvexPolytope& A = f.shapes[a];
    const ConvexPolytope& B = f.shapes[a + 1];
    const double L = std::max(A.boundingRadius(), B.boundingRadius());
    Pose poseA;
    poseA.q = g.rotation();
    // From 2.5 L on one side of A's centroid to 2.5 L on the other, passing at 0..0.5 L from it,
    // turning by one radian in all: steps of 5 L / perTrajectory and 1 / perTrajectory rad.
    const Vector3d dir = g.unit();
    Vector3d side = g.unit().cross(dir);
    side.normalize();
    const Vector3d axis = g.unit();
    const Quaterniond q0 = g.rotation();
    const Vector3d pass = g.uniform(0.0, 0.5) * L * side;
    for (int s = 0; s < perTrajectory; ++s) {
      const double u = static_cast<double>(s) / (perTrajectory - 1);
      Query q;
      q.a = a;
      q.b = a + 1;
      q.poseA = poseA;
      q.poseB.q = (Quaterniond(Eigen::AngleAxisd(u, axis)) * q0).normalized();
      const Vector3d centre_W = poseA.q * A.center() + pass + (2.5 - 5.0 * u) * L * dir;
      q.poseB.t = centre_W - q.poseB.q * B.center();
      f.queries.push_back(q);
    }
  }
  return f;
}

std::optional<Family> robotFamily(int pairs, const std::string& sharedDir) {
  namespace fs = std::filesystem;
  const fs::path robots = fs::path(sharedDir) / "robots";
  if (sharedDir.empty() || !fs::is_directory(robots)) {
    std::cerr << "robots: skipped, the shared robot folder " << robots.string()
              << " is absent (the robot family needs ../shared/robots beside the repository)\n";
    return std::nullopt;
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(robots)) {
    const std::string p = entry.path().string();
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && ext == ".stl" && p.find("collision") != std::string::npos)
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::cerr << "robots: skipped, no collision STL meshes under " << robots.string() << "\n";
    return std::nullopt;
  }
  Family f;
  f.name = "robots";
  Generator g(f.name);
  int totalVertices = 0;
  for (const auto& file : files) {
    f.addShape(readStlVertices(file.string()), file.filename().string());
    totalVertices += f.shapes.back().numVertices();
  }
  f.description = "hulls of the " + std::to_string(files.size()) + " Panda and UR5 collision meshes (" +
                  std::to_string(totalVertices / static_cast<int>(files.size())) +
                  " vertices on average), random overlapping poses";
  const int n = static_cast<int>(f.shapes.size());
  for (int i = 0; i < pairs; ++i) {
    Pose poseA;
    poseA.q = g.rotation();
    poseA.t = 0.1 * g.unit();
    addInsideQuery(f, g, g.index(n), g.index(n), poseA, 0.0, 1.0);
  }
  return f;
}

}  // namespace

std::optional<Family> makeFamily(const std::string& name, int pairs, const std::string& sharedDir) {
  std::optional<Family> family;
  if (name.rfind("verts_", 0) == 0) {
    family = ellipsoidFamily(name, pairs, std::stoi(name.substr(6)));
  } else if (name.rfind("aspect_", 0) == 0) {
    const double aspect = std::stod(name.substr(7));
    Family f;
    f.name = name;
    f.description = "100-vertex hulls between needles and discs, aspect ratio 1:" + name.substr(7);
    Generator g(name);
    addEllipsoidPairs(f, g, pairs, 100, 1.0, 0.0, 1.0, Vector3d::Zero(), true, aspect);
    family = std::move(f);
  } else if (name == "far_1e4") {
    Family f;
    f.name = name;
    f.description = "100-vertex hulls of size 1 placed 1e4 from the world origin";
    Generator g(name);
    for (int i = 0; i < pairs; ++i) addEllipsoidPairs(f, g, 1, 100, 1.0, 0.0, 1.0, 1e4 * g.unit(), false, 1.0);
    family = std::move(f);
  } else if (name == "scale_1e-3" || name == "scale_1e3") {
    const double scale = name == "scale_1e3" ? 1e3 : 1e-3;
    Family f;
    f.name = name;
    f.description = "100-vertex hulls of size " + name.substr(6);
    Generator g(name);
    addEllipsoidPairs(f, g, pairs, 100, scale, 0.0, 1.0, Vector3d::Zero(), false, 1.0);
    family = std::move(f);
  } else if (name == "deep") {
    Family f;
    f.name = name;
    f.description = "100-vertex hulls with B's centroid within 15 % of A's centre-to-vertex distance";
    Generator g(name);
    addEllipsoidPairs(f, g, pairs, 100, 1.0, 0.0, 0.15, Vector3d::Zero(), false, 1.0);
    family = std::move(f);
  } else if (name == "touching" || name == "separated") {
    Family f;
    f.name = name;
    Generator g(name);
    addEllipsoidPairs(f, g, pairs, 100, 1.0, 0.0, 1.0, Vector3d::Zero(), false, 1.0);
    for (std::size_t i = 0; i < f.queries.size(); ++i) {
      Query& q = f.queries[i];
      const double L = f.pairScale(q);
      // touching: signed distance -1e-9 L and +1e-9 L alternately; separated: 1e-4 L .. L.
      const double target =
          name == "touching" ? (i % 2 == 0 ? -1e-9 : 1e-9) * L : std::pow(10.0, g.uniform(-4.0, 0.0)) * L;
      moveToSignedDistance(f, q, target);
    }
    f.description = name == "touching" ? "100-vertex hulls moved to signed distance -1e-9 L and +1e-9 L (alternately)"
                                       : "100-vertex hulls moved apart to distances 1e-4 L .. L";
    family = std::move(f);
  } else if (name == "boxes") {
    family = boxFamily(pairs);
  } else if (name == "polygons") {
    family = polygonFamily(pairs);
  } else if (name == "motion") {
    family = motionFamily(pairs);
  } else if (name == "robots") {
    family = robotFamily(pairs, sharedDir);
  } else {
    throw std::invalid_argument("unknown family '" + name + "'");
  }
  if (!family) return family;
  // Final poses, and the priming poses of the warm start for non-sequence families.
  Generator g(name + "/warm");
  for (Query& q : family->queries) {
    q.X_WA = q.poseA.iso();
    q.X_WB = q.poseB.iso();
    if (!family->sequence) q.primeB = nearbyPose(g, q.poseB, family->pairScale(q));
  }
  return family;
}

}  // namespace deepcheck::bench
