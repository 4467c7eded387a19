// Approximate convex decomposition: recursive plane cuts scored by concavity, then merging and
// vertex reduction (decomposition.h gives the overview and the guarantees).
//
// Parts. A part is the piece of the mesh surface inside a convex cell (the intersection of the
// half-spaces of the cuts that led to it): the mesh triangles clipped to the cell (convex
// polygons), plus the cell's corners that lie inside the solid. Its hull is the hull of those
// points. Coverage: the solid inside the cell is bounded by the polygons and by caps (the solid's
// cut faces) on the cell planes; a cap is bounded by polygon edges and by cell edges, whose ends
// are polygon vertices or cell corners; so the hull holds the caps, hence the solid. Each side of
// a cut is split into components joined through mesh edges and through the regions of the cut
// faces (loops of the cross-section that cross or nest, CrossSection below), never more finely
// than the solid is connected; each cell corner goes to the component whose surface a ray from
// the corner into the cell meets first.
//
// Concavity of a hull: the largest distance from a point of its surface to the mesh solid,
// estimated by sampling the surface and hill-climbing from the worst samples. A sample outside
// the solid is measured against the whole mesh (a BVH query: exact). A sample inside the solid is
// at distance 0; on a part's own hull that only happens on the cell's planes (a surface point
// strictly inside the cell and the solid would be interior to the part, hence to its hull), so
// only samples on hull facets lying on a cut plane are tested, by the 2D winding number of the
// mesh's cross-section by that plane. For merged or reduced pieces, whose hull may reach into the
// solid elsewhere, the value is an upper bound.
//
// Search. Each step cuts the part of largest concavity by the candidate plane that minimizes the
// larger concavity of its sides (ties: the cut along the most mesh face area, then the smaller
// hull volumes). Candidates: the axes and the part's principal axes, through the worst sample,
// through the mesh point nearest to it, through mesh points near it, through the walls that rays
// from it meet (and along those walls' own planes), a few evenly spaced offsets, a refinement of
// the best offset, and slabs between the walls on both sides of the worst sample (a slot or gap
// is cut out in one step). When the best cut does not lower the concavity much (a plateau: a
// hole needs two cuts through its axis, a frame around a pocket a cut along each wall), the most
// promising cuts are compared one cut ahead; if that shows no progress either, the cut along the
// largest mesh face near the concavity is taken.
//
// Departures from the papers. V-HACD voxelizes and cuts the voxel set; CoACD cuts the mesh,
// re-triangulates the caps to keep parts manifold, and searches cut sequences with a Monte-Carlo
// tree. Here caps are never built (their extent is the cell corners', their inside the cross
// sections'), and the search is greedy with the one-cut lookahead, slabs and wall cuts above.

#include "deepcheck/robots/decomposition.h"

#include "decomposition_bvh.h"
#include "decomposition_hull.h"
#include "decomposition_tolerances.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace deepcheck::robots {

using detail::Halfspace;
using detail::Hull;
using detail::PositionKey;
using detail::PositionKeyHash;
using detail::positionKey;
using detail::Triangle;
using detail::TriangleBvh;
using Eigen::Vector3d;
namespace dt = detail::decomp;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.141592653589793;

std::string meshName(const TriangleMesh& mesh) {
  return mesh.source.empty() ? std::string("(generated mesh)") : "'" + mesh.source + "'";
}

std::string formatNumber(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

/// Twice the vector area of a convex polygon given by its corners in order (the sum of the cross
/// products of its fan triangles): its normal, times twice its area.
Vector3d doubleVectorArea(const std::vector<Vector3d>& corners) {
  Vector3d area = Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    area += (corners[k] - corners[0]).cross(corners[k + 1] - corners[0]);
  }
  return area;
}

/// The point where the planes of three half-spaces meet; false when two of them are (nearly)
/// parallel (see kSingularPlanes) or the point is not finite.
bool planesMeet(const Halfspace& a, const Halfspace& b, const Halfspace& c, Vector3d* point) {
  Eigen::Matrix3d A;
  A.row(0) = a.normal;
  A.row(1) = b.normal;
  A.row(2) = c.normal;
  if (std::abs(A.determinant()) < dt::kSingularPlanes) return false;
  *point = A.inverse() * Vector3d(a.offset, b.offset, c.offset);
  return point->allFinite();
}

/// The smallest and largest of d.p over `points`.
struct Extent {
  double lo, hi;
};
Extent extentAlong(const std::vector<Vector3d>& points, const Vector3d& d) {
  Extent e{kInf, -kInf};
  for (const Vector3d& p : points) {
    e.lo = std::min(e.lo, d.dot(p));
    e.hi = std::max(e.hi, d.dot(p));
  }
  return e;
}

// ------------------------------------------------------------------------------------------------
// Deterministic random numbers (splitmix64): the same on every platform, unlike std distributions.

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

// ------------------------------------------------------------------------------------------------
// The input, cleaned: identical vertices welded, degenerate triangles dropped, edge adjacency.

struct CleanMesh {
  std::vector<Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> edgeOf;     ///< 3 per triangle: the undirected edge (v[e], v[e+1 mod 3])
  std::vector<int> edgeStart;  ///< edge k's triangles: edgeTris[edgeStart[k] .. edgeStart[k+1])
  std::vector<int> edgeTris;
  std::vector<int> component;  ///< connected component of each triangle (through edges)
  int numComponents = 0;
  std::vector<int> group;      ///< components with overlapping bounding boxes, per triangle
  int numGroups = 0;
  double diagonal = 0.0;
  bool closed = false;  ///< after filling holes
  int holesFilled = 0;
  int voidsRemoved = 0;    ///< closed inward-facing components sealed inside others
  int inputVertices = 0;   ///< before filling holes
  int inputTriangles = 0;
  double volume = 0.0;  ///< sum of the components' volumes (voids count negative); NaN when open
};

int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

void unite(std::vector<int>& parent, int a, int b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

/// Closes the simple holes of `mesh`: boundary edges (used by one triangle) are chained into
/// loops, and each loop is fanned from a new vertex at its centroid, wound against the triangles
/// around it. A loop through a vertex with several boundary edges is left open. Collision meshes
/// exported from CAD often miss a face or two (a quad of a wall); filling them makes the solid
/// well defined (CrossSection, cell corners). The fill lies in the hull of its loop, so it does
/// not enlarge any piece; returns the number of holes filled.
int fillHoles(CleanMesh* mesh) {
  std::unordered_map<std::uint64_t, int> count;
  auto key = [](int a, int b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
  };
  for (const auto& t : mesh->triangles) {
    for (int e = 0; e < 3; ++e) ++count[key(t[e], t[(e + 1) % 3])];
  }
  std::unordered_map<int, std::vector<int>> next;  // boundary edges a -> b, as the triangles run
  for (const auto& t : mesh->triangles) {
    for (int e = 0; e < 3; ++e) {
      if (count[key(t[e], t[(e + 1) % 3])] == 1) next[t[e]].push_back(t[(e + 1) % 3]);
    }
  }
  int filled = 0;
  std::unordered_map<int, char> used;
  for (const auto& [start, outs] : next) {
    if (used[start] || outs.size() != 1) continue;
    std::vector<int> loop = {start};
    bool simple = true;
    int v = outs.front();
    while (v != start) {
      const auto it = next.find(v);
      if (it == next.end() || it->second.size() != 1 || used[v] ||
          static_cast<int>(loop.size()) > static_cast<int>(next.size())) {
        simple = false;
        break;
      }
      loop.push_back(v);
      v = it->second.front();
    }
    for (int u : loop) used[u] = 1;
    if (!simple || loop.size() < 3) continue;
    Vector3d centroid = Vector3d::Zero();
    for (int u : loop) centroid += mesh->vertices[u];
    centroid /= static_cast<double>(loop.size());
    const int c = static_cast<int>(mesh->vertices.size());
    mesh->vertices.push_back(centroid);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      // The triangles run a -> b along the hole; the fill runs b -> a.
      mesh->triangles.push_back({loop[(k + 1) % loop.size()], loop[k], c});
    }
    ++filled;
  }
  return filled;
}

/// Edge adjacency, closedness and connected components of mesh->triangles.
void buildTopology(CleanMesh* mesh) {
  CleanMesh& out = *mesh;
  const int numTriangles = static_cast<int>(out.triangles.size());
  std::vector<std::pair<std::uint64_t, int>> keys;
  keys.reserve(3 * numTriangles);
  for (int t = 0; t < numTriangles; ++t) {
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::uint64_t>(out.triangles[t][e]);
      const auto b = static_cast<std::uint64_t>(out.triangles[t][(e + 1) % 3]);
      keys.emplace_back(std::min(a, b) << 32 | std::max(a, b), 3 * t + e);
    }
  }
  std::sort(keys.begin(), keys.end());
  out.edgeOf.assign(3 * numTriangles, -1);
  out.edgeStart.clear();
  out.edgeTris.clear();
  out.closed = true;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    const int edge = static_cast<int>(out.edgeStart.size());
    out.edgeStart.push_back(static_cast<int>(out.edgeTris.size()));
    for (; j < keys.size() && keys[j].first == keys[i].first; ++j) {
      out.edgeOf[keys[j].second] = edge;
      out.edgeTris.push_back(keys[j].second / 3);
    }
    if ((j - i) % 2 != 0) out.closed = false;
    i = j;
  }
  out.edgeStart.push_back(static_cast<int>(out.edgeTris.size()));
  std::vector<int> parent(numTriangles);
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t k = 0; k + 1 < out.edgeStart.size(); ++k) {
    for (int i = out.edgeStart[k] + 1; i < out.edgeStart[k + 1]; ++i) {
      unite(parent, out.edgeTris[out.edgeStart[k]], out.edgeTris[i]);
    }
  }
  out.component.assign(numTriangles, -1);
  out.numComponents = 0;
  std::vector<int> label(numTriangles, -1);
  for (int t = 0; t < numTriangles; ++t) {
    const int r = findRoot(parent, t);
    if (label[r] < 0) label[r] = out.numComponents++;
    out.component[t] = label[r];
  }
}

/// Signed volume of each component (divergence theorem, relative to `origin` for precision).
std::vector<double> componentVolumes(const CleanMesh& mesh, const Vector3d& origin) {
  std::vector<double> volume(mesh.numComponents, 0.0);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vector3d a = mesh.vertices[tri[0]] - origin;
    const Vector3d b = mesh.vertices[tri[1]] - origin;
    const Vector3d c = mesh.vertices[tri[2]] - origin;
    volume[mesh.component[t]] += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

CleanMesh cleanMesh(const TriangleMesh& mesh) {
  const std::string name = meshName(mesh);
  if (mesh.triangles.empty()) {
    throw std::invalid_argument("decomposeConvex: mesh " + name + " has no triangles");
  }
  const int n = static_cast<int>(mesh.vertices.size());
  for (int i = 0; i < n; ++i) {
    if (!mesh.vertices[i].allFinite()) {
      const Vector3d& v = mesh.vertices[i];
      throw std::invalid_argument("decomposeConvex: mesh " + name + ": vertex " + std::to_string(i) +
                                  " is not finite (" + formatNumber(v.x()) + ", " +
                                  formatNumber(v.y()) + ", " + formatNumber(v.z()) + ")");
    }
  }
  CleanMesh out;
  // Weld bit-identical positions (after turning -0 into +0).
  std::unordered_map<PositionKey, int, PositionKeyHash> index;
  std::vector<int> remap(n, -1);
  auto weld = [&](int i) {
    if (remap[i] >= 0) return remap[i];
    auto [it, inserted] = index.emplace(positionKey(mesh.vertices[i]), static_cast<int>(out.vertices.size()));
    if (inserted) out.vertices.push_back(mesh.vertices[i]);
    return remap[i] = it->second;
  };
  Vector3d lo = Vector3d::Constant(kInf);
  Vector3d hi = -lo;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    for (int k : mesh.triangles[t]) {
      if (k < 0 || k >= n) {
        throw std::invalid_argument("decomposeConvex: mesh " + name + ": triangle " +
                                    std::to_string(t) + " has vertex index " + std::to_string(k) +
                                    " out of range [0, " + std::to_string(n) + ")");
      }
      lo = lo.cwiseMin(mesh.vertices[k]);
      hi = hi.cwiseMax(mesh.vertices[k]);
    }
  }
  out.diagonal = (hi - lo).norm();
  const double minArea2 = std::pow(dt::kDegenerateRelative * out.diagonal, 4);
  for (const auto& tri : mesh.triangles) {
    const std::array<int, 3> w{weld(tri[0]), weld(tri[1]), weld(tri[2])};
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
    const Vector3d area = (out.vertices[w[1]] - out.vertices[w[0]])
                              .cross(out.vertices[w[2]] - out.vertices[w[0]]);
    if (0.25 * area.squaredNorm() <= minArea2) continue;
    out.triangles.push_back(w);
  }
  if (out.triangles.empty() || !(out.diagonal > 0.0)) {
    throw std::invalid_argument("decomposeConvex: mesh " + name + ": all " +
                                std::to_string(mesh.triangles.size()) +
                                " triangles are degenerate (zero area)");
  }
  // Keep only the vertices that triangles use, so the report counts what is decomposed.
  {
    std::vector<int> used(out.vertices.size(), -1);
    std::vector<Vector3d> kept;
    for (auto& tri : out.triangles) {
      for (int& k : tri) {
        if (used[k] < 0) {
          used[k] = static_cast<int>(kept.size());
          kept.push_back(out.vertices[k]);
        }
        k = used[k];
      }
    }
    out.vertices = std::move(kept);
    lo = Vector3d::Constant(kInf);
    hi = -lo;
    for (const Vector3d& v : out.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    out.diagonal = (hi - lo).norm();
  }

  out.inputVertices = static_cast<int>(out.vertices.size());
  out.inputTriangles = static_cast<int>(out.triangles.size());
  out.holesFilled = fillHoles(&out);

  buildTopology(&out);
  // Orientation. Inside-out components are common in scene meshes, and the cross-section winding
  // numbers need consistent ones: a component of negative volume is flipped, unless it is a void
  // (an inward-facing surface inside another component: most of its surface, probed at up to
  // kVoidProbes of its largest triangles, has a generalized winding number >= 1/2 with respect
  // to the other components). Voids are removed: a cavity sealed inside a solid cannot be
  // reached, so covering it costs nothing, and the decomposition need not work around it.
  const Vector3d origin = 0.5 * (lo + hi);
  std::vector<double> volume = componentVolumes(out, origin);
  {
    const int numTriangles = static_cast<int>(out.triangles.size());
    std::vector<std::vector<int>> byComponent(out.numComponents);
    for (int t = 0; t < numTriangles; ++t) byComponent[out.component[t]].push_back(t);
    auto solidAngleSum = [&](const Vector3d& p, int skipComponent) {
      double sum = 0.0;
      for (int t = 0; t < numTriangles; ++t) {
        if (out.component[t] == skipComponent) continue;
        const auto& tri = out.triangles[t];
        const Vector3d a = out.vertices[tri[0]] - p;
        const Vector3d b = out.vertices[tri[1]] - p;
        const Vector3d c = out.vertices[tri[2]] - p;
        const double la = a.norm();
        const double lb = b.norm();
        const double lc = c.norm();
        // Van Oosterom and Strackee: tan(omega / 2) = det / (la lb lc + (a.b) lc + (b.c) la + (c.a) lb).
        sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
      }
      return sum / (4.0 * kPi);
    };
    std::vector<char> flip(out.numComponents, 0);
    std::vector<char> isVoid(out.numComponents, 0);
    for (int c = 0; c < out.numComponents; ++c) {
      if (!(volume[c] < 0.0)) continue;
      std::vector<std::pair<double, int>> largest;
      for (int t : byComponent[c]) {
        const auto& tri = out.triangles[t];
        const double area = (out.vertices[tri[1]] - out.vertices[tri[0]]).cross(out.vertices[tri[2]] - out.vertices[tri[0]]).norm();
        largest.emplace_back(-area, t);
      }
      const int probes = std::min<int>(dt::kVoidProbes, static_cast<int>(largest.size()));
      std::partial_sort(largest.begin(), largest.begin() + probes, largest.end());
      int inside = 0;
      for (int k = 0; k < probes; ++k) {
        const auto& tri = out.triangles[largest[k].second];
        const Vector3d centroid = (out.vertices[tri[0]] + out.vertices[tri[1]] + out.vertices[tri[2]]) / 3.0;
        if (std::abs(solidAngleSum(centroid, c)) >= 0.5) ++inside;
      }
      isVoid[c] = 2 * inside > probes && out.closed;
      flip[c] = !isVoid[c];
    }
    std::vector<std::array<int, 3>> kept;
    for (int t = 0; t < numTriangles; ++t) {
      const int c = out.component[t];
      if (isVoid[c]) continue;
      auto tri = out.triangles[t];
      if (flip[c]) std::swap(tri[1], tri[2]);
      kept.push_back(tri);
    }
    for (int c = 0; c < out.numComponents; ++c) out.voidsRemoved += isVoid[c];
    out.triangles = std::move(kept);
    buildTopology(&out);
    volume = componentVolumes(out, origin);
  }
  out.volume = 0.0;
  for (double v : volume) out.volume += v;
  if (!out.closed) out.volume = std::numeric_limits<double>::quiet_NaN();
  const int numTriangles = static_cast<int>(out.triangles.size());

  // Groups: components whose bounding boxes overlap stay together at the start (interpenetrating
  // parts, a part inside another); only separate groups are decomposed separately.
  std::vector<Eigen::AlignedBox3d> boxes(out.numComponents);
  for (int t = 0; t < numTriangles; ++t) {
    for (int k : out.triangles[t]) boxes[out.component[t]].extend(out.vertices[k]);
  }
  std::vector<int> groupParent(out.numComponents);
  std::iota(groupParent.begin(), groupParent.end(), 0);
  const double touch = dt::kOnPlaneRelative * out.diagonal;
  for (int a = 0; a < out.numComponents; ++a) {
    for (int b = a + 1; b < out.numComponents; ++b) {
      Eigen::AlignedBox3d grown = boxes[a];
      grown.min().array() -= touch;
      grown.max().array() += touch;
      if (grown.intersects(boxes[b])) unite(groupParent, a, b);
    }
  }
  std::vector<int> groupLabel(out.numComponents, -1);
  out.group.resize(numTriangles);
  for (int t = 0; t < numTriangles; ++t) {
    const int root = findRoot(groupParent, out.component[t]);
    if (groupLabel[root] < 0) groupLabel[root] = out.numGroups++;
    out.group[t] = groupLabel[root];
  }
  return out;
}

// ------------------------------------------------------------------------------------------------
// Cross-section of the whole mesh by a plane: "is this point of the plane inside the solid", and
// which pieces of the mesh surface are joined through the solid's cut face there.
//
// Each triangle crossing the plane gives one segment, oriented along n x (triangle normal): for a
// closed outward-facing mesh (cleanMesh orients every closed component outward) the section's
// loops then run counter-clockwise about n around solid regions, and the winding number is +1
// inside (overlapping components add up). A vertex on the plane counts as above it (symbolic
// perturbation), so every edge is crossed consistently and the loops close even when the plane
// passes through vertices. Crossing points are computed from the edge's lower-index end, so the
// two triangles of an edge produce the same point.
//
// Closed meshes: crossing-number winding, with segments bucketed along the second plane axis so
// that a query scans one bucket. Open meshes: the generalized winding number (the signed angle the
// segments subtend, over 2 pi, inside when >= 1/2), which degrades gracefully at holes.
//
// Regions (only for the planes of accepted cuts): segments chain into loops through the mesh
// edges they cross; loops that cross or nest are joined into one region. The cut face of the
// solid is a union of regions, and two surface pieces bordering the same region may be connected
// through the solid (see components()).

class CrossSection {
 public:
  CrossSection(const CleanMesh& mesh, const Vector3d& normal, double offset, bool withRegions) {
    generalized_ = !mesh.closed;
    const Vector3d helper = std::abs(normal.x()) < 0.6 ? Vector3d::UnitX() : Vector3d::UnitY();
    u_ = normal.cross(helper).normalized();
    v_ = normal.cross(u_);
    std::vector<double> s(mesh.vertices.size());
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = normal.dot(mesh.vertices[i]) - offset;
    std::vector<int> segmentEdges;  // 2 per segment: the mesh edges at its ends
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
      const auto& tri = mesh.triangles[t];
      const bool up0 = s[tri[0]] >= 0.0;
      const bool up1 = s[tri[1]] >= 0.0;
      const bool up2 = s[tri[2]] >= 0.0;
      if (up0 == up1 && up1 == up2) continue;
      Vector3d ends[2];
      int edges[2] = {-1, -1};
      int found = 0;
      for (int e = 0; e < 3; ++e) {
        int a = tri[e];
        int b = tri[(e + 1) % 3];
        if ((s[a] >= 0.0) == (s[b] >= 0.0)) continue;
        if (a > b) std::swap(a, b);
        if (found < 2) {
          const double t01 = s[a] / (s[a] - s[b]);
          ends[found] = mesh.vertices[a] + t01 * (mesh.vertices[b] - mesh.vertices[a]);
          edges[found] = mesh.edgeOf[3 * t + e];
        }
        ++found;
      }
      if (found != 2) continue;
      const Vector3d& A = mesh.vertices[tri[0]];
      const Vector3d triNormal = (mesh.vertices[tri[1]] - A).cross(mesh.vertices[tri[2]] - A);
      if ((ends[1] - ends[0]).dot(normal.cross(triNormal)) < 0.0) {
        std::swap(ends[0], ends[1]);
        std::swap(edges[0], edges[1]);
      }
      segments_.push_back({u_.dot(ends[0]), v_.dot(ends[0]), u_.dot(ends[1]), v_.dot(ends[1]), t});
      segmentEdges.insert(segmentEdges.end(), {edges[0], edges[1]});
    }
    buildBuckets();
    if (withRegions) buildRegions(segmentEdges);
  }

  /// True when p (a point on the plane) is inside the solid's cross-section.
  bool contains(const Vector3d& p) const {
    if (segments_.empty()) return false;
    const double pu = u_.dot(p);
    const double pv = v_.dot(p);
    return windingAt(pu, pv);
  }

  /// Region of the cut face bordered by the segment of mesh triangle `triangle` (-1: none).
  int regionOfTriangle(int triangle) const {
    const auto it = regionOfTriangle_.find(triangle);
    return it == regionOfTriangle_.end() ? -1 : it->second;
  }

  /// Region with a loop enclosing p, a point on the plane (-1: none). Enclosing loops nest, so
  /// they all belong to one region.
  int regionAt(const Vector3d& p) const {
    const double pu = u_.dot(p);
    const double pv = v_.dot(p);
    for (std::size_t l = 0; l < loops_.size(); ++l) {
      if (insideLoop(pu, pv, loops_[l])) return loopRegion_[l];
    }
    return -1;
  }

 private:
  struct Segment {
    double au, av, bu, bv;
    int triangle;
  };

  bool insideLoop(double pu, double pv, const std::vector<int>& loop) const {
    bool inside = false;
    for (int k : loop) {
      const Segment& s = segments_[k];
      if ((s.av > pv) != (s.bv > pv)) {
        const double u = s.au + (pv - s.av) / (s.bv - s.av) * (s.bu - s.au);
        if (u > pu) inside = !inside;
      }
    }
    return inside;
  }

  int bucketOf(double v) const {
    const int b = static_cast<int>((v - vlo_) / width_);
    return std::clamp(b, 0, static_cast<int>(buckets_.size()) - 1);
  }

  void buildBuckets() {
    if (generalized_ || segments_.empty()) return;
    double vlo = kInf;
    double vhi = -kInf;
    for (const Segment& seg : segments_) {
      vlo = std::min({vlo, seg.av, seg.bv});
      vhi = std::max({vhi, seg.av, seg.bv});
    }
    const int numBuckets = std::clamp(static_cast<int>(segments_.size() / 4), 1, 512);
    vlo_ = vlo;
    width_ = (vhi - vlo) / numBuckets;
    if (!(width_ > 0.0)) width_ = 1.0;
    buckets_.assign(numBuckets, {});
    for (int i = 0; i < static_cast<int>(segments_.size()); ++i) {
      const Segment& seg = segments_[i];
      if (seg.av == seg.bv) continue;  // horizontal: never crosses a horizontal ray
      const int b0 = bucketOf(std::min(seg.av, seg.bv));
      const int b1 = bucketOf(std::max(seg.av, seg.bv));
      for (int b = b0; b <= b1; ++b) buckets_[b].push_back(i);
    }
  }

  /// Winding test of (pu, pv): against all segments (generalized winding number), or against the
  /// bucket of pv (crossing number).
  bool windingAt(double pu, double pv) const {
    const std::vector<int>* subset = buckets_.empty() ? nullptr : &buckets_[bucketOf(pv)];
    const int n = subset != nullptr ? static_cast<int>(subset->size()) : static_cast<int>(segments_.size());
    if (generalized_) {
      double angle = 0.0;
      for (int k = 0; k < n; ++k) {
        const Segment& s = segments_[subset != nullptr ? (*subset)[k] : k];
        const double ax = s.au - pu;
        const double ay = s.av - pv;
        const double bx = s.bu - pu;
        const double by = s.bv - pv;
        angle += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      }
      return std::abs(angle) >= kPi;  // |winding| >= 1/2
    }
    int winding = 0;
    for (int k = 0; k < n; ++k) {
      const Segment& s = segments_[subset != nullptr ? (*subset)[k] : k];
      const double side = (s.bu - s.au) * (pv - s.av) - (pu - s.au) * (s.bv - s.av);
      if (s.av <= pv && pv < s.bv) {
        if (side > 0.0) ++winding;  // upward crossing to the right of p
      } else if (s.bv <= pv && pv < s.av) {
        if (side < 0.0) --winding;  // downward crossing to the right of p
      }
    }
    return winding != 0;
  }

  void buildRegions(const std::vector<int>& segmentEdges) {
    const int n = static_cast<int>(segments_.size());
    if (n == 0) return;
    // Loops: segments sharing a crossed mesh edge. (At a non-manifold edge several loops may
    // join: that only merges regions, which is the safe direction.)
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::unordered_map<int, int> firstAtEdge;
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 2; ++k) {
        auto [it, inserted] = firstAtEdge.emplace(segmentEdges[2 * i + k], i);
        if (!inserted) unite(parent, i, it->second);
      }
    }
    std::vector<int> loopOf(n);
    std::vector<std::vector<int>> loops;
    std::unordered_map<int, int> loopIndex;
    for (int i = 0; i < n; ++i) {
      auto [it, inserted] = loopIndex.emplace(findRoot(parent, i), static_cast<int>(loops.size()));
      if (inserted) loops.emplace_back();
      loops[it->second].push_back(i);
      loopOf[i] = it->second;
    }
    // Regions: loops that cross each other or lie one inside the other (at any depth, any mesh
    // components) are joined. This is coarser than the true regions of the cut face (a solid rod
    // standing in a tube's hole joins the tube), which only merges more: the safe direction. It
    // needs no consistent orientation, and voids (inward-facing components) join their body.
    const int numLoops = static_cast<int>(loops.size());
    std::vector<int> loopParent(numLoops);
    std::iota(loopParent.begin(), loopParent.end(), 0);
    auto cross = [](double ax, double ay, double bx, double by, double cx, double cy) {
      return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    };
    auto segmentsMeet = [&](const Segment& p, const Segment& q) {
      const double d1 = cross(p.au, p.av, p.bu, p.bv, q.au, q.av);
      const double d2 = cross(p.au, p.av, p.bu, p.bv, q.bu, q.bv);
      const double d3 = cross(q.au, q.av, q.bu, q.bv, p.au, p.av);
      const double d4 = cross(q.au, q.av, q.bu, q.bv, p.bu, p.bv);
      return ((d1 <= 0.0 && d2 >= 0.0) || (d1 >= 0.0 && d2 <= 0.0)) &&
             ((d3 <= 0.0 && d4 >= 0.0) || (d3 >= 0.0 && d4 <= 0.0));
    };
    std::vector<std::array<double, 4>> boxes(numLoops, {kInf, kInf, -kInf, -kInf});
    for (int a = 0; a < numLoops; ++a) {
      for (int k : loops[a]) {
        const Segment& s = segments_[k];
        boxes[a] = {std::min({boxes[a][0], s.au, s.bu}), std::min({boxes[a][1], s.av, s.bv}),
                    std::max({boxes[a][2], s.au, s.bu}), std::max({boxes[a][3], s.av, s.bv})};
      }
    }
    for (int a = 0; a < numLoops; ++a) {
      for (int b = a + 1; b < numLoops; ++b) {
        if (boxes[a][0] > boxes[b][2] || boxes[b][0] > boxes[a][2] || boxes[a][1] > boxes[b][3] ||
            boxes[b][1] > boxes[a][3]) {
          continue;  // disjoint boxes: neither crossing nor nesting
        }
        const Segment& pa = segments_[loops[a].front()];
        const Segment& pb = segments_[loops[b].front()];
        bool joined = insideLoop(0.5 * (pa.au + pa.bu), 0.5 * (pa.av + pa.bv), loops[b]) ||
                      insideLoop(0.5 * (pb.au + pb.bu), 0.5 * (pb.av + pb.bv), loops[a]);
        for (std::size_t x = 0; !joined && x < loops[a].size(); ++x) {
          for (std::size_t y = 0; !joined && y < loops[b].size(); ++y) {
            joined = segmentsMeet(segments_[loops[a][x]], segments_[loops[b][y]]);
          }
        }
        if (joined) unite(loopParent, a, b);
      }
    }
    std::vector<int> region(numLoops);
    for (int a = 0; a < numLoops; ++a) region[a] = findRoot(loopParent, a);
    loops_ = std::move(loops);
    loopRegion_ = region;
    for (int i = 0; i < n; ++i) regionOfTriangle_[segments_[i].triangle] = region[loopOf[i]];
  }

  bool generalized_ = false;
  Vector3d u_;
  Vector3d v_;
  std::vector<Segment> segments_;
  double vlo_ = 0.0;
  double width_ = 1.0;
  std::vector<std::vector<int>> buckets_;
  std::unordered_map<int, int> regionOfTriangle_;
  std::vector<std::vector<int>> loops_;  ///< segment indices of each loop
  std::vector<int> loopRegion_;
};

// ------------------------------------------------------------------------------------------------
// Concavity of a hull by surface sampling.

/// What a hull is measured against: the union of some parts' triangles (optionally clipped by a
/// half-space), and the cut planes whose cross-sections say where the plane is inside the solid.
struct Cap {
  Vector3d normal;
  double offset;
  const CrossSection* section;
};

struct Target {
  const TriangleBvh* mesh = nullptr;  ///< the whole mesh's triangles
  std::vector<Cap> caps;
};

struct Concavity {
  double value = 0.0;
  bool aborted = false;  ///< stopped once value exceeded the caller's bound
  bool hasWorst = false;
  Vector3d worstSample = Vector3d::Zero();
  Vector3d worstNearest = Vector3d::Zero();  ///< the mesh point nearest to worstSample
};

/// Which fixed points of the hull's triangles are sampled besides the random ones.
enum class Extra {
  None,   ///< random samples only (candidate cuts, which are many)
  Dense,  ///< each triangle's centroid and edge midpoints (parts, merges, the final report):
          ///< catches thin slivers of hull and maxima on hull edges
};

/// Samples `count` random points on the surface of `hull` (area-weighted), plus the `extra`
/// points, and returns the largest distance to `target`.
/// Stops as soon as the largest distance exceeds `abortAbove` (aborted = true).
Concavity measureConcavity(const Hull& hull, const Target& target, int count, Extra extra,
                           std::uint64_t seed, double abortAbove, double diagonal,
                           const Vector3d* hint = nullptr) {
  Concavity result;
  const int numTriangles = static_cast<int>(hull.triangles.size());
  if (numTriangles == 0 || !(hull.area > 0.0)) return result;  // a segment or point: on the mesh
  // Cap plane of each hull triangle (-1: none).
  std::vector<int> capOf(numTriangles, -1);
  for (int t = 0; t < numTriangles; ++t) {
    for (int c = 0; c < static_cast<int>(target.caps.size()); ++c) {
      const double cosine = hull.normals[t].dot(target.caps[c].normal);
      if (std::abs(cosine) < 1.0 - dt::kOnPlaneNormal) continue;
      const double offset = cosine > 0.0 ? target.caps[c].offset : -target.caps[c].offset;
      if (std::abs(hull.offsets[t] - offset) <= dt::kOnPlaneRelative * diagonal) {
        capOf[t] = c;
        break;
      }
    }
  }
  std::vector<double> cumulative(numTriangles);
  double total = 0.0;
  for (int t = 0; t < numTriangles; ++t) {
    const auto& tri = hull.triangles[t];
    total += 0.5 * (hull.vertices[tri[1]] - hull.vertices[tri[0]])
                       .cross(hull.vertices[tri[2]] - hull.vertices[tri[0]])
                       .norm();
    cumulative[t] = total;
  }
  std::vector<std::pair<Vector3d, int>> samples;
  samples.reserve(count + 1 + 4 * numTriangles);
  if (hint != nullptr) {
    // The hull surface point nearest to the hint (where the parent's worst sample was) first: a
    // concavity that survives a cut is found there even if the random samples miss it.
    double best = kInf;
    int bestTriangle = -1;
    Vector3d bestPoint = *hint;
    for (int t = 0; t < numTriangles; ++t) {
      const auto& tri = hull.triangles[t];
      const Vector3d q = detail::closestPointOnTriangle(*hint, hull.vertices[tri[0]], hull.vertices[tri[1]],
                                                        hull.vertices[tri[2]]);
      const double d = (q - *hint).squaredNorm();
      if (d < best) {
        best = d;
        bestTriangle = t;
        bestPoint = q;
      }
    }
    if (bestTriangle >= 0) samples.emplace_back(bestPoint, bestTriangle);
  }
  Rng rng(seed);
  for (int i = 0; i < count; ++i) {
    const double pick = rng.uniform() * total;
    const int t = std::min<int>(
        static_cast<int>(std::upper_bound(cumulative.begin(), cumulative.end(), pick) -
                         cumulative.begin()),
        numTriangles - 1);
    const auto& tri = hull.triangles[t];
    // Uniform point in a triangle: reflect the unit square's upper half onto the lower one.
    double a = rng.uniform();
    double b = rng.uniform();
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const Vector3d& p0 = hull.vertices[tri[0]];
    samples.emplace_back(p0 + a * (hull.vertices[tri[1]] - p0) + b * (hull.vertices[tri[2]] - p0), t);
  }
  if (extra != Extra::None) {
    for (int t = 0; t < numTriangles; ++t) {
      const auto& tri = hull.triangles[t];
      const Vector3d& p0 = hull.vertices[tri[0]];
      const Vector3d& p1 = hull.vertices[tri[1]];
      const Vector3d& p2 = hull.vertices[tri[2]];
      samples.emplace_back((p0 + p1 + p2) / 3.0, t);
      samples.emplace_back(0.5 * (p0 + p1), t);
      samples.emplace_back(0.5 * (p1 + p2), t);
      samples.emplace_back(0.5 * (p2 + p0), t);
    }
  }
  // Distance of a sample on hull triangle t to the target, or a value <= `floor` when it is known
  // not to exceed `floor` (then `nearest` is not set).
  auto distanceOf = [&](const Vector3d& p, int t, double floor, Vector3d* nearest) {
    if (capOf[t] >= 0 && target.caps[capOf[t]].section->contains(p)) return 0.0;  // inside
    Vector3d q;
    const double d = target.mesh->distance(p, nullptr, floor, &q);
    if (d > floor) *nearest = q;
    return d;
  };
  // Seeds for the refinement: the last few samples that raised the maximum.
  std::vector<std::pair<Vector3d, int>> seeds;
  for (const auto& [p, t] : samples) {
    Vector3d nearest = p;
    const double d = distanceOf(p, t, result.value, &nearest);
    if (d <= result.value) continue;
    result.value = d;
    result.hasWorst = std::isfinite(d);
    result.worstSample = p;
    result.worstNearest = nearest;
    seeds.emplace_back(p, t);
    if (result.value > abortAbove) {
      result.aborted = true;
      return result;
    }
  }
  // Refinement: the maximum of the distance over a facet is usually a small spot (the middle of a
  // hole spanned by the hull) that a few random samples find only roughly. Hill-climb from the
  // last seeds within their hull triangles, halving the step when no neighbour is farther.
  const int refineSeeds = extra == Extra::None ? dt::kCandidateRefineSeeds : dt::kRefineSeeds;
  const int refineSteps = extra == Extra::None ? dt::kCandidateRefineSteps : dt::kRefineSteps;
  const int firstSeed = std::max(0, static_cast<int>(seeds.size()) - refineSeeds);
  for (int k = static_cast<int>(seeds.size()) - 1; k >= firstSeed; --k) {
    Vector3d p = seeds[k].first;
    const int t = seeds[k].second;
    const auto& tri = hull.triangles[t];
    const Vector3d& a = hull.vertices[tri[0]];
    const Vector3d e1 = hull.vertices[tri[1]] - a;
    const Vector3d e2 = hull.vertices[tri[2]] - a;
    const Vector3d normal = e1.cross(e2);
    const double area2 = normal.squaredNorm();
    if (!(area2 > 0.0)) continue;
    // Barycentric coordinates of p in the triangle, to stay inside it.
    auto inside = [&](const Vector3d& x) {
      const Vector3d r = x - a;
      const double u = r.cross(e2).dot(normal) / area2;
      const double v = e1.cross(r).dot(normal) / area2;
      return u >= 0.0 && v >= 0.0 && u + v <= 1.0;
    };
    const Vector3d ux = e1.normalized();
    const Vector3d uy = normal.cross(e1).normalized();
    Vector3d nearest = p;
    double value = distanceOf(p, t, 0.0, &nearest);
    double step = 0.25 * std::sqrt(std::sqrt(area2));
    for (int iteration = 0; iteration < refineSteps && step > dt::kOnPlaneRelative * diagonal; ++iteration) {
      bool moved = false;
      for (int dirIndex = 0; dirIndex < 6; ++dirIndex) {
        const double angle = dirIndex * kPi / 3.0;
        const Vector3d x = p + step * (std::cos(angle) * ux + std::sin(angle) * uy);
        if (!inside(x)) continue;
        Vector3d q = x;
        const double d = distanceOf(x, t, value, &q);
        if (d > value) {
          value = d;
          p = x;
          nearest = q;
          moved = true;
        }
      }
      if (!moved) step *= 0.5;
    }
    if (value > result.value) {
      result.value = value;
      result.worstSample = p;
      result.worstNearest = nearest;
      result.hasWorst = std::isfinite(value);
      if (result.value > abortAbove) {
        result.aborted = true;
        return result;
      }
    }
  }
  return result;
}

// ------------------------------------------------------------------------------------------------
// Parts and the decomposer.

/// A convex polygon of a part: a mesh triangle clipped to the part's cell.
struct PartPolygon {
  std::vector<Vector3d> corners;
  int source;  ///< index of the mesh triangle it was clipped from
};

/// A cut plane and the mesh's cross-section by it.
struct CutPlane {
  Vector3d normal;
  double offset;
  CrossSection section;
};

struct CellSide {
  int plane;     ///< index into the decomposer's cut planes
  bool flipped;  ///< false: the part keeps n.x <= d; true: n.x >= d
};

struct Part {
  std::vector<CellSide> cell;
  std::vector<PartPolygon> polygons;
  /// Corners of the cell inside the solid and bordering this part: the solid's cut faces end
  /// there, so the hull needs them (the cut faces are not in the polygons).
  std::vector<Vector3d> cellCorners;
  std::vector<Vector3d> points;  ///< distinct corners of the polygons, and the cell corners
  Hull hull;                     ///< hull of the points
  Hull finalHull;                ///< hull, reduced to the vertex budget when it met the target
  double hullConcavity = 0.0;    ///< concavity of `hull`
  double concavity = 0.0;        ///< concavity of `finalHull`: what has to meet the target
  bool reductionLimited = false; ///< hull meets the target, but not once reduced
  bool hasWorst = false;
  Vector3d worstSample = Vector3d::Zero();   ///< hull surface point farthest from the part
  Vector3d worstNearest = Vector3d::Zero();  ///< the part's point nearest to it
  bool unsplittable = false;  ///< no valid cut was found
  bool reduced = false;       ///< finishPart ran
  bool noSlivers = false;     ///< a sliver cut made no progress: cuts leaving a sliver are skipped
};

struct Piece {
  std::vector<int> parts;
  Hull hull;       ///< hull of the parts' points
  Hull finalHull;  ///< hull reduced to the vertex budget
  double concavity = 0.0;  ///< of finalHull
};

class Decomposer {
 public:
  /// `target`: the absolute concavity target; decisions aim at kDecisionFraction of it.
  Decomposer(const CleanMesh& mesh, const DecompositionParams& params, double target)
      : mesh_(mesh),
        params_(params),
        target_(dt::kDecisionFraction * target),
        reportTarget_(target),
        diagonal_(mesh.diagonal) {
    std::vector<Triangle> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) triangles.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
    meshBvh_ = TriangleBvh(std::move(triangles));
  }

  /// Runs the whole algorithm; fills `pieces` (hulls, reduced) and the concavity fields of `report`.
  std::vector<ConvexPiece> run(DecompositionReport* report);

 private:
  std::uint64_t nextSeed() { return params_.seed ^ (0x9e3779b97f4a7c15ULL * ++evaluations_); }
  Halfspace halfspaceOf(const CellSide& side) const {
    const CutPlane& plane = *planes_[side.plane];
    return side.flipped ? Halfspace{-plane.normal, -plane.offset} : Halfspace{plane.normal, plane.offset};
  }
  void addCaps(const Part& part, std::vector<Cap>* caps) const {
    for (const CellSide& side : part.cell) {
      const CutPlane& plane = *planes_[side.plane];
      caps->push_back({plane.normal, plane.offset, &plane.section});
    }
  }

  /// A part from its cell and polygons: points, hull, concavity; with `reduce`, finishPart too.
  /// `hint`: where the parent's worst hull sample was (sampled first, see measureConcavity).
  Part makePart(std::vector<CellSide> cell, std::vector<PartPolygon> polygons,
                std::vector<Vector3d> cellCorners, bool reduce = true, const Vector3d* hint = nullptr);
  /// Reduces the part's hull to the vertex budget (once) and measures the reduced hull.
  void finishPart(Part* part);
  struct Component {
    std::vector<PartPolygon> polygons;
    std::vector<Vector3d> cellCorners;
  };
  std::vector<Component> components(std::vector<PartPolygon> polygons,
                                    const std::vector<CellSide>& cell) const;
  std::vector<PartPolygon> clip(const std::vector<PartPolygon>& polygons, const Halfspace& keep) const;
  /// Corners of the cell (vertices of the intersection of its half-spaces) inside the solid, with
  /// the cell planes through each.
  struct CellCorner {
    Vector3d point;
    std::vector<int> planes;  ///< indices into the cell
  };
  std::vector<CellCorner> solidCellCorners(const std::vector<CellSide>& cell) const;

  struct SideResult {
    bool valid = false;
    bool aborted = false;
    double concavity = 0.0;
    double volume = 0.0;
    int vertices = 0;
  };
  /// A half-space a side keeps, with the mesh's cross-section by its plane.
  struct Keep {
    Halfspace plane;
    const CrossSection* section;
  };
  /// Hull and concavity of the part's side within all `keeps` (one cut, or the middle of a slab).
  SideResult evaluateSide(const Part& part, const std::vector<Keep>& keeps, double abortAbove);
  /// A scored cut: `cut` keeps its negative side for one child, the positive side for the other.
  struct Candidate {
    Halfspace cut;
    double score;   ///< larger concavity of the two sides
    double volume;  ///< sum of the two sides' hull volumes
    int vertices;   ///< larger hull vertex count of the two sides
    bool throughWorst;
    double faceArea;  ///< area of the part's polygons lying in the plane (a wall cut along)
    int direction;    ///< index of its normal among the part's cut directions (axes first)
    /// A slab: a second, parallel cut at this larger offset (NaN for a single cut). The part is
    /// cut in three: below `cut`, between the two planes, above this one.
    double slabOffset = std::numeric_limits<double>::quiet_NaN();
    bool isSlab() const { return !std::isnan(slabOffset); }
  };
  /// Splits `part` by the candidate (one cut, or the two planes of a slab).
  std::vector<Part> applyCut(const Part& part, const Candidate& candidate, bool reduce);
  /// Scores the candidate cuts of `part` (decomposition.h lists them); `quick`: fewer offsets and
  /// no refinement. Cuts scoring above `bound` are dropped early.
  std::vector<Candidate> scoreCuts(const Part& part, bool quick, double bound, double* bestScore);
  const Candidate* pickBest(const Part& part, const std::vector<Candidate>& scored,
                            double bestScore) const;
  /// Tie-break between two cuts of equal score.
  bool betterTie(const Candidate& a, const Candidate& b) const;
  /// Chooses the cut of `part` (with a one-cut lookahead on plateaus) and returns its children.
  bool chooseSplit(const Part& part, std::vector<Part>* children);
  std::vector<Part> split(const Part& part, const Halfspace& cut, bool reduce = true);

  Hull pieceHull(const Piece& a, const Piece* b) const;
  Target pieceTarget(const Piece& a, const Piece* b) const;
  double mergeCost(const Piece& a, const Piece& b, double abortAbove);
  std::vector<Piece> merge(std::vector<Piece> pieces, bool forced);

  const CleanMesh& mesh_;
  const DecompositionParams& params_;
  const double target_;        ///< what decisions aim at
  const double reportTarget_;  ///< what the report checks
  const double diagonal_;
  TriangleBvh meshBvh_;
  std::set<std::pair<int, int>> forbidden_;  ///< parts whose merge failed the final check
  std::vector<std::unique_ptr<CutPlane>> planes_;
  std::vector<Part> parts_;
  int budget_ = 0;  ///< pieces allowed in the current budget stage (see run), <= maxPieces
  std::uint64_t evaluations_ = 0;
};

std::vector<PartPolygon> Decomposer::clip(const std::vector<PartPolygon>& polygons,
                                          const Halfspace& keep) const {
  std::vector<PartPolygon> out;
  out.reserve(polygons.size());
  const double minArea = std::pow(dt::kDegenerateRelative * diagonal_, 2);
  std::vector<Vector3d> clipped;
  const double onPlane = dt::kOnPlaneRelative * diagonal_;
  for (const PartPolygon& polygon : polygons) {
    bool allIn = true;
    bool allOut = true;
    bool inPlane = true;
    for (const Vector3d& p : polygon.corners) {
      const double d = keep.signedDistance(p);
      allIn = allIn && d <= 0.0;
      allOut = allOut && d > 0.0;
      inPlane = inPlane && std::abs(d) <= onPlane;
    }
    if (inPlane) {
      // A face lying in the cut plane goes to the side its solid is on (against its outward
      // normal): on the other side it would be a flat part of its own.
      if (doubleVectorArea(polygon.corners).dot(keep.normal) > 0.0) out.push_back(polygon);
      continue;
    }
    if (allIn) {
      out.push_back(polygon);
      continue;
    }
    if (allOut) continue;
    detail::clipPolygon(polygon.corners, keep, &clipped);
    if (clipped.size() < 3) continue;
    if (0.5 * doubleVectorArea(clipped).norm() <= minArea) continue;
    out.push_back({clipped, polygon.source});
  }
  return out;
}

std::vector<Decomposer::CellCorner> Decomposer::solidCellCorners(const std::vector<CellSide>& cell) const {
  std::vector<CellCorner> corners;
  const int k = static_cast<int>(cell.size());
  if (k < 3) return corners;
  std::vector<Halfspace> h;
  for (const CellSide& side : cell) h.push_back(halfspaceOf(side));
  const double tolerance = dt::kOnPlaneRelative * diagonal_;
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      for (int c = b + 1; c < k; ++c) {
        Vector3d p;
        bool feasible = planesMeet(h[a], h[b], h[c], &p);
        for (int i = 0; feasible && i < k; ++i) feasible = h[i].signedDistance(p) <= tolerance;
        if (!feasible) continue;
        bool known = false;
        for (CellCorner& corner : corners) {
          if ((corner.point - p).norm() <= tolerance) {
            for (int plane : {a, b, c}) {
              if (std::find(corner.planes.begin(), corner.planes.end(), plane) == corner.planes.end()) {
                corner.planes.push_back(plane);
              }
            }
            known = true;
            break;
          }
        }
        if (known) continue;
        if (!planes_[cell[a].plane]->section.contains(p)) continue;
        corners.push_back({p, {a, b, c}});
      }
    }
  }
  return corners;
}

std::vector<Decomposer::Component> Decomposer::components(std::vector<PartPolygon> polygons,
                                                          const std::vector<CellSide>& cell) const {
  // Union-find over the source triangles present, plus one node per (cut plane, region) of the
  // cell's faces. Two source triangles are joined when they share a mesh edge whose segment meets
  // the cell (both clipped polygons then contain that part of the edge); a source triangle is
  // joined to the region of each cell plane its segment borders (the solid connects through the
  // cut face). Joining too much is safe (a piece is then larger than needed); splitting a
  // connected solid would not be (the hulls of its surface pieces need not cover it).
  std::unordered_map<int, int> node;
  std::vector<int> sources;
  for (const PartPolygon& polygon : polygons) {
    if (node.emplace(polygon.source, static_cast<int>(sources.size())).second) sources.push_back(polygon.source);
  }
  std::vector<int> parent(sources.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<Halfspace> halfspaces;
  for (const CellSide& side : cell) halfspaces.push_back(halfspaceOf(side));
  auto edgeMeetsCell = [&](const Vector3d& a, const Vector3d& b) {
    double t0 = 0.0;
    double t1 = 1.0;
    for (const Halfspace& h : halfspaces) {
      const double sa = h.signedDistance(a);
      const double sb = h.signedDistance(b);
      if (sa > 0.0 && sb > 0.0) return false;
      if (sa > 0.0) t0 = std::max(t0, sa / (sa - sb));
      if (sb > 0.0) t1 = std::min(t1, sa / (sa - sb));
    }
    return t0 <= t1;
  };
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const int t = sources[i];
    for (int e = 0; e < 3; ++e) {
      const int edge = mesh_.edgeOf[3 * t + e];
      bool checked = false;
      bool meets = false;
      for (int k = mesh_.edgeStart[edge]; k < mesh_.edgeStart[edge + 1]; ++k) {
        const int other = mesh_.edgeTris[k];
        if (other == t) continue;
        auto it = node.find(other);
        if (it == node.end()) continue;
        if (!checked) {
          const auto& tri = mesh_.triangles[t];
          meets = edgeMeetsCell(mesh_.vertices[tri[e]], mesh_.vertices[tri[(e + 1) % 3]]);
          checked = true;
        }
        if (meets) unite(parent, static_cast<int>(i), it->second);
      }
    }
  }
  std::map<std::pair<int, int>, int> regionNode;
  auto join = [&](int sourceNode, int plane, int region) {
    auto [it, inserted] = regionNode.emplace(std::make_pair(plane, region), static_cast<int>(parent.size()));
    if (inserted) parent.push_back(it->second);
    unite(parent, sourceNode, it->second);
  };
  const double onPlane = dt::kOnPlaneRelative * diagonal_;
  for (std::size_t c = 0; c < cell.size(); ++c) {
    const CrossSection& section = planes_[cell[c].plane]->section;
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const int region = section.regionOfTriangle(sources[i]);
      if (region >= 0) join(static_cast<int>(i), cell[c].plane, region);
    }
    // A polygon that reaches the plane borders the region there, even when its mesh triangle's
    // own segment lies outside the cell (a body around a void whose walls it does not share).
    for (const PartPolygon& polygon : polygons) {
      for (const Vector3d& p : polygon.corners) {
        if (std::abs(halfspaces[c].signedDistance(p)) > onPlane) continue;
        const int region = section.regionAt(p);
        if (region >= 0) join(node[polygon.source], cell[c].plane, region);
        break;
      }
    }
  }
  std::vector<int> label(parent.size(), -1);
  std::vector<Component> out;
  for (PartPolygon& polygon : polygons) {
    const int root = findRoot(parent, node[polygon.source]);
    if (label[root] < 0) {
      label[root] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[label[root]].polygons.push_back(std::move(polygon));
  }
  // Cell corners inside the solid: the solid's cut faces end there, so the hull of the component
  // whose solid holds the corner must include it. That component is found by casting a ray from
  // the corner into the cell: the ray runs inside that solid until it meets the solid's surface,
  // and the first polygon it meets is that component's. A component that touches no cell plane
  // may be a void inside the solid (an inner boundary): then the first component touching the
  // cell's planes along the ray gets the corner too. A corner whose rays all leave the cell first
  // goes to every component (safe).
  std::vector<char> touchesCell(out.size(), 0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (const PartPolygon& polygon : out[i].polygons) {
      for (const Vector3d& p : polygon.corners) {
        for (const Halfspace& h : halfspaces) touchesCell[i] = touchesCell[i] || std::abs(h.signedDistance(p)) <= onPlane;
      }
    }
  }
  for (const CellCorner& corner : solidCellCorners(cell)) {
    Vector3d inward = Vector3d::Zero();
    for (int c : corner.planes) inward -= halfspaces[c].normal;
    const Vector3d axis = inward.normalized();
    std::vector<int> owners;
    for (int attempt = 0; owners.empty() && attempt < dt::kCornerRays && axis.allFinite(); ++attempt) {
      // The axis, then the axis tilted away from each of the corner's planes in turn.
      Vector3d dir = axis;
      if (attempt > 0) dir = (axis - 0.5 * halfspaces[corner.planes[attempt % corner.planes.size()]].normal).normalized();
      double exit = kInf;
      for (const Halfspace& h : halfspaces) {
        const double rate = h.normal.dot(dir);
        if (rate > 0.0) exit = std::min(exit, -h.signedDistance(corner.point) / rate);
      }
      double first = exit;
      double firstTouching = exit;
      int firstOwner = -1;
      int touchingOwner = -1;
      for (int i = 0; i < static_cast<int>(out.size()); ++i) {
        for (const PartPolygon& polygon : out[i].polygons) {
          for (std::size_t k = 1; k + 1 < polygon.corners.size(); ++k) {
            const double t = detail::rayTriangle(corner.point, dir, polygon.corners[0], polygon.corners[k],
                                                 polygon.corners[k + 1]);
            if (!(t > 0.0)) continue;
            if (t < first) {
              first = t;
              firstOwner = i;
            }
            if (touchesCell[i] && t < firstTouching) {
              firstTouching = t;
              touchingOwner = i;
            }
          }
        }
      }
      if (firstOwner >= 0) owners.push_back(firstOwner);
      if (firstOwner >= 0 && !touchesCell[firstOwner] && touchingOwner >= 0) owners.push_back(touchingOwner);
    }
    // No owner found: every component gets the corner (safe), but only for a closed mesh. An open
    // mesh has no well-defined solid (its inside test is fuzzy near holes), so there only corners
    // with an owner are added; its surface is covered either way.
    if (owners.empty() && mesh_.closed) {
      for (int i = 0; i < static_cast<int>(out.size()); ++i) owners.push_back(i);
    }
    for (int i : owners) out[i].cellCorners.push_back(corner.point);
  }
  return out;
}

Part Decomposer::makePart(std::vector<CellSide> cell, std::vector<PartPolygon> polygons,
                          std::vector<Vector3d> cellCorners, bool reduce, const Vector3d* hint) {
  Part part;
  part.cell = std::move(cell);
  part.polygons = std::move(polygons);
  part.cellCorners = std::move(cellCorners);
  std::unordered_set<PositionKey, PositionKeyHash> seen;
  auto addPoint = [&](const Vector3d& p) {
    if (seen.insert(positionKey(p)).second) part.points.push_back(p);
  };
  for (const PartPolygon& polygon : part.polygons) {
    for (const Vector3d& p : polygon.corners) addPoint(p);
  }
  for (const Vector3d& p : part.cellCorners) addPoint(p);
  part.hull = detail::convexHull(part.points);
  Target target;
  target.mesh = &meshBvh_;
  addCaps(part, &target.caps);
  const Concavity c = measureConcavity(part.hull, target, dt::kPartSamples, Extra::Dense, nextSeed(), kInf,
                                       diagonal_, hint);
  part.hullConcavity = c.value;
  part.concavity = c.value;
  part.hasWorst = c.hasWorst;
  part.worstSample = c.worstSample;
  part.worstNearest = c.worstNearest;
  part.finalHull = part.hull;
  if (reduce) finishPart(&part);
  return part;
}

void Decomposer::finishPart(Part* part) {
  if (part->reduced) return;
  part->reduced = true;
  // Only a hull that meets the target is worth reducing: the others will be cut anyway.
  if (part->hullConcavity > target_ ||
      static_cast<int>(part->hull.vertices.size()) <= params_.maxVerticesPerPiece) {
    return;
  }
  part->finalHull = detail::reduceHullVertices(part->hull, params_.maxVerticesPerPiece);
  Target target;
  target.mesh = &meshBvh_;
  addCaps(*part, &target.caps);
  part->concavity = measureConcavity(part->finalHull, target, dt::kPartSamples, Extra::Dense,
                                     nextSeed(), kInf, diagonal_)
                        .value;
  part->reductionLimited = part->concavity > target_;
}

Decomposer::SideResult Decomposer::evaluateSide(const Part& part, const std::vector<Keep>& keeps,
                                                double abortAbove) {
  SideResult result;
  std::vector<Vector3d> points;
  points.reserve(part.points.size());
  std::unordered_set<PositionKey, PositionKeyHash> crossings;
  const double slab = dt::kMinSlabRelative * diagonal_;
  const double tolerance = dt::kOnPlaneRelative * diagonal_;
  auto insideKeeps = [&](const Vector3d& x, std::size_t skip) {
    for (std::size_t k = 0; k < keeps.size(); ++k) {
      if (k != skip && keeps[k].plane.signedDistance(x) > tolerance) return false;
    }
    return true;
  };
  for (const PartPolygon& polygon : part.polygons) {
    const std::size_t n = polygon.corners.size();
    for (std::size_t e = 0; e < n; ++e) {
      const Vector3d& a = polygon.corners[e];
      const Vector3d& b = polygon.corners[(e + 1) % n];
      bool deep = true;
      for (const Keep& keep : keeps) deep = deep && keep.plane.signedDistance(a) < -slab;
      if (deep) result.valid = true;
      for (std::size_t k = 0; k < keeps.size(); ++k) {
        const double sa = keeps[k].plane.signedDistance(a);
        const double sb = keeps[k].plane.signedDistance(b);
        // Each mesh edge is crossed in the two polygons that share it: compute it once, from the
        // lexicographically smaller end, and keep the first copy.
        if (!((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0))) continue;
        const bool forward = std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        const Vector3d& from = forward ? a : b;
        const Vector3d& to = forward ? b : a;
        const double sf = forward ? sa : sb;
        const double st = forward ? sb : sa;
        const Vector3d x = from + (sf / (sf - st)) * (to - from);
        if (!insideKeeps(x, k)) continue;
        if (crossings.insert(positionKey(x)).second) points.push_back(x);
      }
    }
  }
  if (!result.valid) return result;
  for (const Vector3d& p : part.points) {
    if (insideKeeps(p, keeps.size())) points.push_back(p);  // polygon corners and cell corners
  }
  // New cell corners on each cut plane: where it meets the edges of the part's cell (and the
  // other cut plane), inside the solid and inside the part's hull (corners of other parts sharing
  // the cell stay out).
  std::vector<Halfspace> others;
  for (const CellSide& side : part.cell) others.push_back(halfspaceOf(side));
  for (const Keep& keep : keeps) others.push_back(keep.plane);
  for (const Keep& keep : keeps) {
    for (std::size_t a = 0; a < others.size(); ++a) {
      for (std::size_t b = a + 1; b < others.size(); ++b) {
        Vector3d p;
        bool feasible = planesMeet(keep.plane, others[a], others[b], &p);
        for (std::size_t i = 0; feasible && i < others.size(); ++i) {
          feasible = others[i].signedDistance(p) <= tolerance;
        }
        for (std::size_t f = 0; feasible && f < part.hull.triangles.size(); ++f) {
          feasible = part.hull.normals[f].dot(p) - part.hull.offsets[f] <= tolerance;
        }
        if (feasible && keep.section->contains(p)) points.push_back(p);
      }
    }
  }
  const Hull hull = detail::convexHull(points);
  Target target;
  target.mesh = &meshBvh_;
  addCaps(part, &target.caps);
  for (const Keep& keep : keeps) target.caps.push_back({keep.plane.normal, keep.plane.offset, keep.section});
  const Vector3d* hint = part.hasWorst ? &part.worstSample : nullptr;
  const Concavity c = measureConcavity(hull, target, dt::kCandidateSamples, Extra::None, nextSeed(),
                                       abortAbove, diagonal_, hint);
  result.aborted = c.aborted;
  result.concavity = c.value;
  result.volume = hull.volume;
  result.vertices = static_cast<int>(hull.vertices.size());
  return result;
}

std::vector<Decomposer::Candidate> Decomposer::scoreCuts(const Part& part, bool quick, double bound,
                                                         double* bestScore) {
  // Directions: the axes, then the part's principal axes unless they repeat an axis.
  std::vector<Vector3d> directions = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  {
    Vector3d center = Vector3d::Zero();
    for (const Vector3d& p : part.points) center += p;
    center /= static_cast<double>(part.points.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vector3d& p : part.points) cov += (p - center) * (p - center).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    for (int i = 2; i >= 0; --i) {
      const Vector3d d = solver.eigenvectors().col(i).normalized();
      bool repeated = false;
      for (const Vector3d& e : directions) repeated = repeated || std::abs(d.dot(e)) > dt::kSameDirectionCos;
      if (!repeated && d.allFinite()) directions.push_back(d);
    }
  }
  std::vector<Extent> ranges;
  for (const Vector3d& d : directions) ranges.push_back(extentAlong(part.points, d));

  std::vector<Candidate> scored;
  *bestScore = kInf;
  const double tie = dt::kTieFraction * target_;
  const double slab = dt::kMinSlabRelative * diagonal_;
  std::vector<std::pair<int, double>> tried;
  auto tryCut = [&](int dir, double offset, bool throughWorst) {
    const Extent& r = ranges[dir];
    if (!(offset > r.lo + slab && offset < r.hi - slab)) return;
    // A plane (almost) tried already: the same cut.
    for (const auto& [d, o] : tried) {
      if (d == dir && std::abs(o - offset) <= dt::kSameOffsetFraction * target_) return;
    }
    tried.emplace_back(dir, offset);
    const Vector3d& n = directions[dir];
    const CrossSection section(mesh_, n, offset, false);
    double abortAbove = std::min(*bestScore + tie, bound);
    if (part.reductionLimited) abortAbove = std::max(abortAbove, target_);
    const SideResult a = evaluateSide(part, {{{n, offset}, &section}}, abortAbove);
    if (!a.valid || a.aborted) return;
    const SideResult b = evaluateSide(part, {{{-n, -offset}, &section}}, abortAbove);
    if (!b.valid || b.aborted) return;
    if (part.noSlivers && std::min(a.volume, b.volume) < (1.0 - dt::kSliverVolume) * part.hull.volume) return;
    const double score = std::max(a.concavity, b.concavity);
    *bestScore = std::min(*bestScore, score);
    double faceArea = 0.0;
    const double onPlane = dt::kOnPlaneRelative * diagonal_;
    for (const PartPolygon& polygon : part.polygons) {
      bool inPlane = true;
      for (const Vector3d& p : polygon.corners) inPlane = inPlane && std::abs(n.dot(p) - offset) <= onPlane;
      if (!inPlane) continue;
      faceArea += 0.5 * doubleVectorArea(polygon.corners).norm();
    }
    scored.push_back({{n, offset}, score, a.volume + b.volume, std::max(a.vertices, b.vertices), throughWorst,
                      faceArea, dir});
  };

  // Through the worst hull sample (the middle of the deepest concavity: cutting there splits it)
  // and through the mesh point nearest to it (the bottom of the concavity).
  if (part.hasWorst) {
    for (int d = 0; d < static_cast<int>(directions.size()); ++d) {
      tryCut(d, directions[d].dot(part.worstSample), true);
      tryCut(d, directions[d].dot(part.worstNearest), false);
    }
  }
  // Through the part's points near the worst sample: the walls, floors and edges that bound the
  // concavity (the walls of a slot, the rim of a hole), which the two planes above may miss.
  if (part.hasWorst) {
    const double radius = 1.5 * part.concavity + target_;
    std::vector<const Vector3d*> near;
    for (const Vector3d& p : part.points) {
      if ((p - part.worstSample).norm() <= radius) near.push_back(&p);
    }
    for (int d = 0; d < static_cast<int>(directions.size()); ++d) {
      const double center = directions[d].dot(part.worstSample);
      std::vector<double> values;
      for (const Vector3d* p : near) values.push_back(directions[d].dot(*p));
      std::sort(values.begin(), values.end(), [&](double a, double b) { return std::abs(a - center) < std::abs(b - center); });
      std::vector<double> chosen;
      for (double v : values) {
        bool close = false;
        for (double c : chosen) close = close || std::abs(c - v) <= dt::kFeatureSpacingFraction * target_;
        if (!close) chosen.push_back(v);
        if (static_cast<int>(chosen.size()) >= (quick ? dt::kQuickFeatureOffsets : dt::kFeatureOffsets)) break;
      }
      for (double v : chosen) tryCut(d, v, false);
    }
  }
  // Through the walls around the concavity: the first surface hit by rays from the worst sample
  // along each direction, both ways (the floor, ceiling and sides of a pocket or slot, which may
  // be farther than the points above).
  // The plane of the wall hit is a candidate too (a drafted wall is not axis-aligned).
  std::vector<double> wallAbove(directions.size(), kInf);
  std::vector<double> wallBelow(directions.size(), -kInf);
  if (part.hasWorst) {
    const int fixedDirections = static_cast<int>(directions.size());
    for (int d = 0; d < fixedDirections; ++d) {
      for (double sign : {1.0, -1.0}) {
        const Vector3d dir = sign * directions[d];
        double nearest = kInf;
        const PartPolygon* wall = nullptr;
        for (const PartPolygon& polygon : part.polygons) {
          for (std::size_t k = 1; k + 1 < polygon.corners.size(); ++k) {
            const double t = detail::rayTriangle(part.worstSample, dir, polygon.corners[0],
                                                 polygon.corners[k], polygon.corners[k + 1]);
            if (t > 0.0 && t < nearest) {
              nearest = t;
              wall = &polygon;
            }
          }
        }
        if (!std::isfinite(nearest)) continue;
        const Vector3d hit = part.worstSample + nearest * dir;
        tryCut(d, directions[d].dot(hit), false);
        (sign > 0.0 ? wallAbove : wallBelow)[d] = directions[d].dot(hit);
        Vector3d normal = doubleVectorArea(wall->corners);
        if (!(normal.norm() > 0.0)) continue;
        normal.normalize();
        bool known = false;
        for (const Vector3d& e : directions) known = known || std::abs(normal.dot(e)) > 1.0 - dt::kOnPlaneNormal;
        if (known) continue;
        directions.push_back(normal);
        ranges.push_back(extentAlong(part.points, normal));
        tryCut(static_cast<int>(directions.size()) - 1, normal.dot(hit), false);
      }
    }
  }
  // Slabs between the walls on both sides of the worst sample: a slot, groove or gap between two
  // walls is cut out in one step (three parts), which no single cut shows as progress.
  for (int d = 0; d < static_cast<int>(wallAbove.size()); ++d) {
    const double lo = wallBelow[d];
    const double hi = wallAbove[d];
    const Extent& r = ranges[d];
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo > r.lo + slab && hi < r.hi - slab && hi - lo > 2.0 * slab)) {
      continue;
    }
    const Vector3d& n = directions[d];
    const CrossSection sectionLo(mesh_, n, lo, false);
    const CrossSection sectionHi(mesh_, n, hi, false);
    const double abortAbove = std::min(*bestScore + tie, bound);
    const SideResult a = evaluateSide(part, {{{n, lo}, &sectionLo}}, abortAbove);
    if (!a.valid || a.aborted) continue;
    const SideResult b = evaluateSide(part, {{{-n, -lo}, &sectionLo}, {{n, hi}, &sectionHi}}, abortAbove);
    if (!b.valid || b.aborted) continue;
    const SideResult c = evaluateSide(part, {{{-n, -hi}, &sectionHi}}, abortAbove);
    if (!c.valid || c.aborted) continue;
    const double score = std::max({a.concavity, b.concavity, c.concavity});
    *bestScore = std::min(*bestScore, score);
    Candidate slabCut{{n, lo}, score, a.volume + b.volume + c.volume,
                      std::max({a.vertices, b.vertices, c.vertices}), false, 0.0, d};
    slabCut.slabOffset = hi;
    scored.push_back(slabCut);
  }
  if (quick) return scored;  // the lookahead's second cut: the planes near the concavity only
  const int offsets = dt::kOffsetsPerDirection;
  for (int d = 0; d < static_cast<int>(directions.size()); ++d) {
    const Extent& r = ranges[d];
    for (int i = 0; i < offsets; ++i) tryCut(d, r.lo + (r.hi - r.lo) * (i + 0.5) / offsets, false);
  }
  if (scored.empty()) return scored;
  // Refine the offset of the best cut.
  for (int round = 1; round <= dt::kRefinementRounds; ++round) {
    const Candidate* pick = pickBest(part, scored, *bestScore);
    if (pick->isSlab()) break;
    const int dir = pick->direction;
    const double offset = pick->cut.offset;
    const Extent& r = ranges[dir];
    const double step = (r.hi - r.lo) / offsets / std::pow(2.0, round);
    tryCut(dir, offset - step, false);
    tryCut(dir, offset + step, false);
  }
  return scored;
}

bool Decomposer::betterTie(const Candidate& a, const Candidate& b) const {
  const double areaTie = dt::kFaceAreaTie * diagonal_ * diagonal_;
  if (std::abs(a.faceArea - b.faceArea) > areaTie) return a.faceArea > b.faceArea;
  return a.volume < b.volume;
}

const Decomposer::Candidate* Decomposer::pickBest(const Part& part, const std::vector<Candidate>& scored,
                                                   double bestScore) const {
  // Among the cuts within `tie` of the best score: the one along the most mesh face area first
  // (cutting along a wall of a pocket or slot is progress that the concavities only show once
  // all its walls are cut), then the smaller sum of hull volumes. A part cut only because its reduced hull misses the target
  // (reductionLimited) needs fewer hull vertices per side rather than less concavity: among the
  // cuts whose sides meet the target, the smaller larger vertex count wins.
  const double tie = dt::kTieFraction * target_;
  const Candidate* pick = nullptr;
  if (part.reductionLimited) {
    for (const Candidate& s : scored) {
      if (s.score > target_) continue;
      if (pick == nullptr || s.vertices < pick->vertices ||
          (s.vertices == pick->vertices && s.volume < pick->volume)) {
        pick = &s;
      }
    }
    if (pick != nullptr) return pick;
  }
  for (const Candidate& s : scored) {
    if (s.score > bestScore + tie) continue;
    if (pick == nullptr || betterTie(s, *pick)) pick = &s;
  }
  return pick;
}

bool Decomposer::chooseSplit(const Part& part, std::vector<Part>* children) {
  double bestScore = kInf;
  std::vector<Candidate> scored = scoreCuts(part, false, kInf, &bestScore);
  if (scored.empty()) return false;
  const Candidate* pick = pickBest(part, scored, bestScore);
  // The children are reduced to the vertex budget only once chosen (finishChildren).
  auto finishChildren = [&]() {
    for (Part& kid : *children) finishPart(&kid);
    return !children->empty();
  };
  *children = applyCut(part, *pick, false);
  // The sides' concavities as the children measure them (more samples than the candidates had).
  double greedy = 0.0;
  for (const Part& kid : *children) greedy = std::max(greedy, kid.concavity);
  const bool plateau = !part.reductionLimited && greedy > target_ &&
                       greedy > dt::kPlateauFraction * part.concavity;
  if (!plateau) return finishChildren();
  // Plateau: no single cut lowers the worst concavity (a slot needs a cut along each wall, a hole
  // two cuts through its axis). Look one cut ahead: split by each of the most promising cuts, and
  // score it by the worst concavity left after the best quick cut of each side that misses the
  // target.
  // First cuts tried: through the worst sample (a hole needs two of those), the nearest cut on
  // each side of it along each direction (a slot needs one along each wall), and the best scores.
  std::vector<const Candidate*> order = {pick};
  auto add = [&](const Candidate* c) {
    if (c != nullptr && std::find(order.begin(), order.end(), c) == order.end()) order.push_back(c);
  };
  // Equal scores are common on a plateau: the axes and principal directions go first.
  auto byScore = [](const Candidate* a, const Candidate* b) {
    if (a->score != b->score) return a->score < b->score;
    if (a->direction != b->direction) return a->direction < b->direction;
    return a->volume < b->volume;
  };
  std::vector<const Candidate*> through;
  std::vector<const Candidate*> walls;
  for (const Candidate& c : scored) {
    if (c.throughWorst) {
      through.push_back(&c);
      continue;
    }
    // Is c the nearest cut on its side of the worst sample, along its direction?
    const double x = c.cut.signedDistance(part.worstSample);
    bool nearest = true;
    for (const Candidate& o : scored) {
      if (o.throughWorst || &o == &c || (o.cut.normal - c.cut.normal).squaredNorm() > 0.0) continue;
      const double y = o.cut.signedDistance(part.worstSample);
      if ((x > 0.0) == (y > 0.0) && std::abs(y) < std::abs(x)) nearest = false;
    }
    if (nearest) walls.push_back(&c);
  }
  std::sort(through.begin(), through.end(), byScore);
  std::sort(walls.begin(), walls.end(), byScore);
  for (std::size_t k = 0; k < std::max(through.size(), walls.size()); ++k) {
    if (k < through.size()) add(through[k]);
    if (k < walls.size()) add(walls[k]);
  }
  std::vector<const Candidate*> ranked;
  for (const Candidate& c : scored) ranked.push_back(&c);
  std::sort(ranked.begin(), ranked.end(), byScore);
  for (int k = 0; k < dt::kLookaheadBest && k < static_cast<int>(ranked.size()); ++k) {
    order.insert(order.begin() + std::min<std::size_t>(order.size(), 1 + k), ranked[k]);
  }
  // (duplicates from the insertion above are skipped below)
  {
    std::vector<const Candidate*> unique;
    for (const Candidate* c : order) {
      if (std::find(unique.begin(), unique.end(), c) == unique.end()) unique.push_back(c);
    }
    order = std::move(unique);
  }
  if (static_cast<int>(order.size()) > dt::kLookaheadCuts) order.resize(dt::kLookaheadCuts);
  const double tie = dt::kTieFraction * target_;
  double bestAhead = kInf;
  const Candidate* bestCandidate = nullptr;
  for (const Candidate* candidate : order) {
    std::vector<Part> kids = candidate == pick ? std::move(*children) : applyCut(part, *candidate, false);
    double ahead = 0.0;
    for (const Part& kid : kids) {
      double next = kid.concavity;
      if (next > target_) {
        double quickBest = kInf;
        scoreCuts(kid, true, std::min(bestAhead + tie, next), &quickBest);
        next = std::min(next, quickBest);
      }
      ahead = std::max(ahead, next);
      if (ahead > bestAhead + tie) break;
    }
    if (ahead < bestAhead - tie || (ahead <= bestAhead + tie && (bestCandidate == nullptr || betterTie(*candidate, *bestCandidate)))) {
      bestAhead = std::min(bestAhead, ahead);
      bestCandidate = candidate;
      *children = std::move(kids);
    }
  }
  // Still no progress two cuts deep (a frame around a pocket needs a cut along each of its
  // walls before any concavity drops): cut along the largest mesh face near the concavity.
  if (bestAhead > dt::kStructuralFraction * part.concavity) {
    const Candidate* structural = nullptr;
    for (const Candidate& c : scored) {
      if (c.faceArea <= dt::kFaceAreaTie * diagonal_ * diagonal_ || c.score > part.concavity + tie) continue;
      if (structural == nullptr || betterTie(c, *structural)) structural = &c;
    }
    if (structural != nullptr && structural != bestCandidate) *children = applyCut(part, *structural, false);
  }
  return finishChildren();
}

std::vector<Part> Decomposer::applyCut(const Part& part, const Candidate& candidate, bool reduce) {
  std::vector<Part> first = split(part, candidate.cut, reduce && !candidate.isSlab());
  if (!candidate.isSlab()) return first;
  // The second plane of the slab cuts the parts above the first one.
  const Halfspace upper{candidate.cut.normal, candidate.slabOffset};
  std::vector<Part> out;
  for (Part& kid : first) {
    const Extent e = extentAlong(kid.points, upper.normal);
    const double slab = dt::kMinSlabRelative * diagonal_;
    if (e.lo < upper.offset - slab && e.hi > upper.offset + slab) {
      for (Part& piece : split(kid, upper, reduce)) out.push_back(std::move(piece));
    } else {
      if (reduce) finishPart(&kid);
      out.push_back(std::move(kid));
    }
  }
  return out;
}

std::vector<Part> Decomposer::split(const Part& part, const Halfspace& cut, bool reduce) {
  const int plane = static_cast<int>(planes_.size());
  planes_.push_back(std::make_unique<CutPlane>(
      CutPlane{cut.normal, cut.offset, CrossSection(mesh_, cut.normal, cut.offset, true)}));
  std::vector<Part> children;
  for (bool flipped : {false, true}) {
    const Halfspace keep = flipped ? cut.flipped() : cut;
    std::vector<CellSide> cell = part.cell;
    cell.push_back({plane, flipped});
    for (Component& component : components(clip(part.polygons, keep), cell)) {
      children.push_back(makePart(cell, std::move(component.polygons), std::move(component.cellCorners), reduce,
                                  part.hasWorst ? &part.worstSample : nullptr));
    }
  }
  return children;
}

Hull Decomposer::pieceHull(const Piece& a, const Piece* b) const {
  std::vector<Vector3d> points = a.hull.vertices;
  if (b != nullptr) points.insert(points.end(), b->hull.vertices.begin(), b->hull.vertices.end());
  return detail::convexHull(points);
}

Target Decomposer::pieceTarget(const Piece& a, const Piece* b) const {
  Target target;
  target.mesh = &meshBvh_;
  std::vector<int> planes;
  for (const Piece* piece : {&a, b}) {
    if (piece == nullptr) continue;
    for (int p : piece->parts) {
      for (const CellSide& side : parts_[p].cell) planes.push_back(side.plane);
    }
  }
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  for (int p : planes) target.caps.push_back({planes_[p]->normal, planes_[p]->offset, &planes_[p]->section});
  return target;
}

double Decomposer::mergeCost(const Piece& a, const Piece& b, double abortAbove) {
  for (int x : a.parts) {
    for (int y : b.parts) {
      if (forbidden_.count({x, y}) != 0) return kInf;  // merged once, failed the final check
    }
  }
  const Hull hull = pieceHull(a, &b);
  const Target target = pieceTarget(a, &b);
  Concavity c = measureConcavity(hull, target, dt::kPartSamples, Extra::Dense, nextSeed(), abortAbove,
                                 diagonal_);
  if (c.aborted) return kInf;
  if (static_cast<int>(hull.vertices.size()) > params_.maxVerticesPerPiece) {
    const Hull reduced = detail::reduceHullVertices(hull, params_.maxVerticesPerPiece);
    c = measureConcavity(reduced, target, dt::kPartSamples, Extra::Dense, nextSeed(), abortAbove, diagonal_);
    if (c.aborted) return kInf;
  }
  return c.value;
}

std::vector<Piece> Decomposer::merge(std::vector<Piece> pieces, bool forced) {
  // Not forced: neighbours whose merged hull meets the target, cheapest first. Forced: the
  // cheapest pair of all while there are more than maxPieces pieces.
  auto boxOf = [&](const Piece& p) {
    Eigen::AlignedBox3d box;
    for (const Vector3d& v : p.hull.vertices) box.extend(v);
    return box;
  };
  if (forced && static_cast<int>(pieces.size()) <= budget_) return pieces;
  const double bound = forced ? kInf : target_;
  const int n = static_cast<int>(pieces.size());
  std::vector<std::vector<double>> cost(n, std::vector<double>(n, kInf));
  std::vector<Eigen::AlignedBox3d> boxes(n);
  for (int i = 0; i < n; ++i) boxes[i] = boxOf(pieces[i]);
  const double grow = dt::kNeighbourFraction * target_;
  auto neighbours = [&](int i, int j) {
    if (forced) return true;
    Eigen::AlignedBox3d a = boxes[i];
    a.min().array() -= grow;
    a.max().array() += grow;
    return a.intersects(boxes[j]);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (neighbours(i, j)) cost[i][j] = mergeCost(pieces[i], pieces[j], bound);
    }
  }
  std::vector<char> alive(n, 1);
  int count = n;
  for (;;) {
    if (forced && count <= budget_) break;
    int bi = -1;
    int bj = -1;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        if (alive[i] && alive[j] && cost[i][j] < kInf && (bi < 0 || cost[i][j] < cost[bi][bj])) {
          bi = i;
          bj = j;
        }
      }
    }
    if (bi < 0 || (!forced && cost[bi][bj] > target_)) break;
    Piece merged;
    merged.parts = pieces[bi].parts;
    merged.parts.insert(merged.parts.end(), pieces[bj].parts.begin(), pieces[bj].parts.end());
    merged.hull = pieceHull(pieces[bi], &pieces[bj]);
    merged.finalHull = detail::reduceHullVertices(merged.hull, params_.maxVerticesPerPiece);
    merged.concavity = cost[bi][bj];
    pieces[bi] = std::move(merged);
    boxes[bi] = boxOf(pieces[bi]);
    alive[bj] = 0;
    --count;
    for (int k = 0; k < n; ++k) {
      if (!alive[k] || k == bi) continue;
      const int i = std::min(k, bi);
      const int j = std::max(k, bi);
      cost[i][j] = neighbours(i, j) ? mergeCost(pieces[i], pieces[j], bound) : kInf;
    }
  }
  std::vector<Piece> kept;
  for (int i = 0; i < n; ++i) {
    if (alive[i]) kept.push_back(std::move(pieces[i]));
  }
  return kept;
}

std::vector<ConvexPiece> Decomposer::run(DecompositionReport* report) {
  // The whole mesh as one part: if its hull meets the target, it is the answer.
  std::vector<PartPolygon> all;
  all.reserve(mesh_.triangles.size());
  for (int t = 0; t < static_cast<int>(mesh_.triangles.size()); ++t) {
    const auto& tri = mesh_.triangles[t];
    all.push_back({{mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]}, t});
  }
  std::vector<Piece> pieces;
  auto addPart = [&](Part part) {
    pieces.push_back({{static_cast<int>(parts_.size())}, part.hull, part.finalHull, part.concavity});
    parts_.push_back(std::move(part));
  };
  Part whole = makePart({}, all, {});
  report->hullConcavity = whole.hullConcavity;
  report->alreadyConvex = whole.concavity <= target_;
  if (report->alreadyConvex || mesh_.numGroups == 1) {
    addPart(std::move(whole));
  } else {
    std::vector<std::vector<PartPolygon>> byGroup(mesh_.numGroups);
    for (const PartPolygon& polygon : all) byGroup[mesh_.group[polygon.source]].push_back(polygon);
    for (auto& polygons : byGroup) addPart(makePart({}, std::move(polygons), {}));
  }
  // Rounds: cut the worst part until all meet the target or the budget is spent; then merge the
  // neighbours that can be merged, which frees budget for more cuts. Then verify: the final,
  // denser estimate may find a piece above the target that the decisions' estimate missed (a small
  // hole spanned by a hull): such a piece is cut further (or, if merged, split back into its
  // parts) while the budget lasts.
  //
  // Budget stages: all of this runs first with at most kFirstPieceBudget pieces; only when the
  // target is still missed does it go on from there (the pieces above the target reopened) with
  // twice the budget, up to maxPieces. A mesh that meets the target within the first budget gets
  // the same pieces whatever maxPieces is, and a larger maxPieces costs nothing for it.
  std::vector<Concavity> final;
  // Pieces whose final estimate is above the report's target go back to be cut: a part keeps its
  // larger concavity and the worst sample found; a merged piece is split back into its parts.
  // `forbidAll`: none of those parts may be merged together again; otherwise only those of a
  // merge that the decisions had accepted (a forced merge is undone, not judged).
  auto reopen = [&](bool forbidAll) {
    std::vector<Piece> next;
    bool changed = false;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      Piece& piece = pieces[i];
      if (final[i].value <= reportTarget_) {
        next.push_back(std::move(piece));
        continue;
      }
      changed = true;
      if (piece.parts.size() == 1) {
        Part& part = parts_[piece.parts.front()];
        part.concavity = std::max(part.concavity, final[i].value);
        part.hasWorst = final[i].hasWorst;
        part.worstSample = final[i].worstSample;
        part.worstNearest = final[i].worstNearest;
        piece.concavity = part.concavity;
        next.push_back(std::move(piece));
      } else {
        const bool forbid = forbidAll || piece.concavity <= target_;
        for (int a : piece.parts) {
          if (forbid) {
            for (int b : piece.parts) forbidden_.insert({a, b});
          }
          next.push_back({{a}, parts_[a].hull, parts_[a].finalHull, parts_[a].concavity});
        }
      }
    }
    pieces = std::move(next);
    return changed;
  };
  for (budget_ = std::min(params_.maxPieces, dt::kFirstPieceBudget);;
       budget_ = static_cast<int>(std::min<long long>(2LL * budget_, params_.maxPieces))) {
    for (int verify = 0; verify <= dt::kVerifyRounds; ++verify) {
      for (int round = 0; round < dt::kMaxRounds && !report->alreadyConvex; ++round) {
        while (static_cast<int>(pieces.size()) < budget_) {
          int worst = -1;
          for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
            if (pieces[i].parts.size() != 1 || pieces[i].concavity <= target_) continue;
            if (parts_[pieces[i].parts.front()].unsplittable) continue;
            if (worst < 0 || pieces[i].concavity > pieces[worst].concavity) worst = i;
          }
          if (worst < 0) break;
          const int index = pieces[worst].parts.front();
          std::vector<Part> children;
          if (!chooseSplit(parts_[index], &children) || children.empty()) {
            parts_[index].unsplittable = true;
            continue;
          }
          // A cut that only shaves a sliver off (a child with nearly the part's hull volume and its
          // concavity) is no progress: the part is left as it is.
          bool stuck = false;
          for (const Part& child : children) {
            stuck = stuck || (child.hull.volume >= dt::kSliverVolume * parts_[index].hull.volume &&
                              child.concavity >= parts_[index].concavity - dt::kTieFraction * target_);
          }
          if (stuck) {
            // Once more without the sliver cuts, then give up on this part.
            if (parts_[index].noSlivers) parts_[index].unsplittable = true;
            parts_[index].noSlivers = true;
            continue;
          }
          pieces.erase(pieces.begin() + worst);
          for (Part& child : children) addPart(std::move(child));
        }
        bool over = false;
        for (const Piece& piece : pieces) over = over || piece.concavity > target_;
        if (!params_.mergePieces) break;
        const std::size_t before = pieces.size();
        pieces = merge(std::move(pieces), false);
        if (!over || pieces.size() == before) break;
      }
      if (!report->alreadyConvex) pieces = merge(std::move(pieces), true);

      // The final, denser concavity estimate on what is returned.
      final.clear();
      for (const Piece& piece : pieces) {
        final.push_back(measureConcavity(piece.finalHull, pieceTarget(piece, nullptr), dt::kReportSamples,
                                         Extra::Dense, nextSeed(), kInf, diagonal_));
      }
      if (verify == dt::kVerifyRounds || report->alreadyConvex) break;
      if (!reopen(true)) break;
    }
    if (report->alreadyConvex || budget_ >= params_.maxPieces) break;
    bool met = true;
    for (const Concavity& c : final) met = met && c.value <= reportTarget_;
    if (met) break;
    reopen(false);
  }
  std::vector<ConvexPiece> out;
  report->concavity = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Hull& hull = pieces[i].finalHull;
    report->concavity = std::max(report->concavity, final[i].value);
    out.push_back({hull.vertices, hull.triangles, hull.volume, final[i].value});
  }
  return out;
}

}  // namespace

// ------------------------------------------------------------------------------------------------

double DecompositionParams::targetConcavity(double diagonal) const {
  return std::max(maxConcavity * diagonal, minConcavityAbs);
}

void DecompositionParams::validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("DecompositionParams: " + what);
  };
  if (!(maxConcavity > 0.0 && maxConcavity <= 1.0)) {
    fail("maxConcavity must be in (0, 1] (a fraction of the bounding-box diagonal), got " +
         formatNumber(maxConcavity));
  }
  if (!(minConcavityAbs >= 0.0 && std::isfinite(minConcavityAbs))) {
    fail("minConcavityAbs must be finite and >= 0, got " + formatNumber(minConcavityAbs));
  }
  if (maxPieces < 1) fail("maxPieces must be >= 1, got " + std::to_string(maxPieces));
  if (maxVerticesPerPiece < 4) {
    fail("maxVerticesPerPiece must be >= 4, got " + std::to_string(maxVerticesPerPiece));
  }
}

const char* toString(CacheStatus status) {
  switch (status) {
    case CacheStatus::NotUsed: return "not used";
    case CacheStatus::Hit: return "hit";
    case CacheStatus::Stored: return "stored";
    case CacheStatus::Replaced: return "replaced";
    case CacheStatus::StoreFailed: return "store failed";
  }
  return "?";
}

std::vector<deep::ConvexPolytope> ConvexDecomposition::polytopes() const {
  std::vector<deep::ConvexPolytope> out;
  out.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::string name =
        (report.source.empty() ? std::string("mesh") : report.source) + " piece " + std::to_string(i);
    out.push_back(deep::ConvexPolytope::fromPoints(pieces[i].vertices, name));
  }
  return out;
}

ConvexDecomposition decomposeConvex(const TriangleMesh& mesh, const DecompositionParams& params) {
  const auto start = std::chrono::steady_clock::now();
  params.validate();
  const CleanMesh clean = cleanMesh(mesh);
  ConvexDecomposition result;
  DecompositionReport& report = result.report;
  report.source = mesh.source;
  report.numTriangles = clean.inputTriangles;
  report.numVertices = clean.inputVertices;
  report.holesFilled = clean.holesFilled;
  report.voidsRemoved = clean.voidsRemoved;
  report.numComponents = clean.numComponents;
  report.diagonal = clean.diagonal;
  report.targetConcavity = params.targetConcavity(clean.diagonal);
  report.meshClosed = clean.closed;
  report.meshVolume = clean.volume;

  Decomposer decomposer(clean, params, report.targetConcavity);
  result.pieces = decomposer.run(&report);

  report.numPieces = static_cast<int>(result.pieces.size());
  report.concavityRelative = report.concavity / clean.diagonal;
  report.targetMet = report.concavity <= report.targetConcavity;
  report.piecesVolume = 0.0;
  report.maxPieceVertices = 0;
  for (const ConvexPiece& piece : result.pieces) {
    report.piecesVolume += piece.volume;
    report.maxPieceVertices = std::max(report.maxPieceVertices, static_cast<int>(piece.vertices.size()));
  }
  report.volumeRatio = report.meshClosed && report.meshVolume > 0.0
                           ? report.piecesVolume / report.meshVolume
                           : std::numeric_limits<double>::quiet_NaN();
  report.decomposeMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  report.milliseconds = report.decomposeMilliseconds;
  return result;
}

bool pieceContains(const ConvexPiece& piece, const Vector3d& point, double tolerance) {
  if (piece.volume > 0.0 && !piece.triangles.empty()) {
    for (const auto& t : piece.triangles) {
      const Vector3d& a = piece.vertices[t[0]];
      const Vector3d n = (piece.vertices[t[1]] - a).cross(piece.vertices[t[2]] - a);
      const double length = n.norm();
      if (!(length > 0.0)) continue;
      if (n.dot(point - a) / length > tolerance) return false;
    }
    return true;
  }
  // Flat or lower-dimensional: distance to the polygon, segment or point.
  double best = kInf;
  for (const auto& t : piece.triangles) {
    const Vector3d q = detail::closestPointOnTriangle(point, piece.vertices[t[0]], piece.vertices[t[1]],
                                                      piece.vertices[t[2]]);
    best = std::min(best, (q - point).norm());
  }
  if (piece.triangles.empty() && !piece.vertices.empty()) {
    const Vector3d& a = piece.vertices.front();
    const Vector3d& b = piece.vertices.back();
    best = (detail::closestPointOnTriangle(point, a, b, b) - point).norm();
  }
  return best <= tolerance;
}

void writePiecesObj(const std::string& path, const std::vector<ConvexPiece>& pieces) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("writePiecesObj: cannot open '" + path + "' for writing");
  out.precision(17);
  out << "# deepcheck convex decomposition: " << pieces.size() << " pieces\n";
  int base = 1;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    out << "o piece_" << i << "\n";
    for (const Vector3d& v : pieces[i].vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << "\n";
    for (const auto& t : pieces[i].triangles) {
      out << "f " << base + t[0] << ' ' << base + t[1] << ' ' << base + t[2] << "\n";
    }
    base += static_cast<int>(pieces[i].vertices.size());
  }
  out.flush();
  if (!out) throw std::runtime_error("writePiecesObj: error while writing '" + path + "'");
}

}  // namespace deepcheck::robots
