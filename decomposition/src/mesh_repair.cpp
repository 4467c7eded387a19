// Mesh repair for the decomposer: welding, holes, topology, orientation (clean_mesh.h).

#include "clean_mesh.h"

#include "basics.h"
#include "hull.h"
#include "union_find.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace deepcheck::decomposition::detail {

namespace {

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

/// Welds bit-identical positions (after turning -0 into +0) into out->vertices and keeps the
/// triangles that are not degenerate (kDegenerateRelative of the diagonal) in out->triangles.
/// A triangle on the same three vertices as an earlier one (either winding: a repeated or
/// two-sided face) is dropped too: its copies would cancel or double the volume and the
/// cross-section winding numbers.
void weldTriangles(const TriangleMesh& mesh, const std::string& name, CleanMesh* out) {
  std::set<std::array<int, 3>> seen;
  std::unordered_map<PositionKey, int, PositionKeyHash> index;
  std::vector<int> remap(mesh.vertices.size(), -1);
  auto weld = [&](int i) {
    if (remap[i] >= 0) return remap[i];
    auto [it, inserted] = index.emplace(positionKey(mesh.vertices[i]), static_cast<int>(out->vertices.size()));
    if (inserted) out->vertices.push_back(mesh.vertices[i]);
    return remap[i] = it->second;
  };
  for (const auto& tri : mesh.triangles) {
    const std::array<int, 3> w{weld(tri[0]), weld(tri[1]), weld(tri[2])};
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
    if (isDegenerate(out->vertices[w[0]], out->vertices[w[1]], out->vertices[w[2]], out->diagonal)) continue;
    std::array<int, 3> sorted = w;
    std::sort(sorted.begin(), sorted.end());
    if (!seen.insert(sorted).second) {
      ++out->duplicatesRemoved;
      continue;
    }
    out->triangles.push_back(w);
  }
  if (out->triangles.empty() || !(out->diagonal > 0.0)) {
    throw std::invalid_argument("decomposeConvex: mesh " + name + ": all " + std::to_string(mesh.triangles.size()) +
                                " triangles are degenerate (zero area)");
  }
}

/// Keeps only the vertices that triangles use, so the report counts what is decomposed; sets
/// the diagonal of what is left and returns the centre of its bounding box.
Vector3d keepUsedVertices(CleanMesh* out) {
  std::vector<int> used(out->vertices.size(), -1);
  std::vector<Vector3d> kept;
  for (auto& tri : out->triangles) {
    for (int& k : tri) {
      if (used[k] < 0) {
        used[k] = static_cast<int>(kept.size());
        kept.push_back(out->vertices[k]);
      }
      k = used[k];
    }
  }
  out->vertices = std::move(kept);
  Vector3d lo = Vector3d::Constant(kInf);
  Vector3d hi = -lo;
  for (const Vector3d& v : out->vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  out->diagonal = (hi - lo).norm();
  return 0.5 * (lo + hi);
}

/// The generalized winding number at p of the triangles of every component but `skipComponent`
/// (Van Oosterom and Strackee's solid angles, over 4 pi).
double windingNumberOfOthers(const CleanMesh& mesh, const Vector3d& p, int skipComponent) {
  double sum = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    if (mesh.component[t] == skipComponent) continue;
    const auto& tri = mesh.triangles[t];
    const Vector3d a = mesh.vertices[tri[0]] - p;
    const Vector3d b = mesh.vertices[tri[1]] - p;
    const Vector3d c = mesh.vertices[tri[2]] - p;
    const double la = a.norm();
    const double lb = b.norm();
    const double lc = c.norm();
    // Van Oosterom and Strackee: tan(omega / 2) = det / (la lb lc + (a.b) lc + (b.c) la + (c.a) lb).
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4.0 * kPi);
}

/// Whether component c (of negative volume) is a void: most of its surface, probed at up to
/// kVoidProbes of its largest triangles, lies inside the other components.
bool isVoidComponent(const CleanMesh& mesh, const std::vector<int>& triangles, int c) {
  std::vector<std::pair<double, int>> largest;
  for (int t : triangles) {
    const auto& tri = mesh.triangles[t];
    const double area =
        (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]).norm();
    largest.emplace_back(-area, t);
  }
  const int probes = std::min<int>(tol::kVoidProbes, static_cast<int>(largest.size()));
  std::partial_sort(largest.begin(), largest.begin() + probes, largest.end());
  int inside = 0;
  for (int k = 0; k < probes; ++k) {
    const auto& tri = mesh.triangles[largest[k].second];
    const Vector3d centroid = (mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3.0;
    if (std::abs(windingNumberOfOthers(mesh, centroid, c)) >= 0.5) ++inside;
  }
  return 2 * inside > probes && mesh.closed;
}

/// Orientation. Inside-out components are common in scene meshes, and the cross-section winding
/// numbers need consistent ones: a component of negative volume is flipped, unless it is a void
/// (an inward-facing surface inside another component: isVoidComponent). Voids are removed: a
/// cavity sealed inside a solid cannot be reached, so covering it costs nothing, and the
/// decomposition need not work around it. Returns the volumes of the components after that.
std::vector<double> orientComponents(CleanMesh* out, const Vector3d& origin) {
  const std::vector<double> volume = componentVolumes(*out, origin);
  const int numTriangles = static_cast<int>(out->triangles.size());
  std::vector<std::vector<int>> byComponent(out->numComponents);
  for (int t = 0; t < numTriangles; ++t) byComponent[out->component[t]].push_back(t);
  std::vector<char> flip(out->numComponents, 0);
  std::vector<char> isVoid(out->numComponents, 0);
  for (int c = 0; c < out->numComponents; ++c) {
    if (!(volume[c] < 0.0)) continue;
    isVoid[c] = isVoidComponent(*out, byComponent[c], c);
    flip[c] = !isVoid[c];
  }
  std::vector<std::array<int, 3>> kept;
  for (int t = 0; t < numTriangles; ++t) {
    const int c = out->component[t];
    if (isVoid[c]) continue;
    auto tri = out->triangles[t];
    if (flip[c]) std::swap(tri[1], tri[2]);
    kept.push_back(tri);
  }
  for (int c = 0; c < out->numComponents; ++c) out->voidsRemoved += isVoid[c];
  out->triangles = std::move(kept);
  buildTopology(out);
  return componentVolumes(*out, origin);
}

/// Groups: components whose bounding boxes overlap stay together at the start (interpenetrating
/// parts, a part inside another); only separate groups are decomposed separately.
void groupComponents(CleanMesh* out) {
  const int numTriangles = static_cast<int>(out->triangles.size());
  std::vector<Eigen::AlignedBox3d> boxes(out->numComponents);
  for (int t = 0; t < numTriangles; ++t) {
    for (int k : out->triangles[t]) boxes[out->component[t]].extend(out->vertices[k]);
  }
  std::vector<int> groupParent(out->numComponents);
  std::iota(groupParent.begin(), groupParent.end(), 0);
  const double touch = tol::kOnPlaneRelative * out->diagonal;
  for (int a = 0; a < out->numComponents; ++a) {
    for (int b = a + 1; b < out->numComponents; ++b) {
      Eigen::AlignedBox3d grown = boxes[a];
      grown.min().array() -= touch;
      grown.max().array() += touch;
      if (grown.intersects(boxes[b])) unite(groupParent, a, b);
    }
  }
  std::vector<int> groupLabel(out->numComponents, -1);
  out->group.resize(numTriangles);
  for (int t = 0; t < numTriangles; ++t) {
    const int root = findRoot(groupParent, out->component[t]);
    if (groupLabel[root] < 0) groupLabel[root] = out->numGroups++;
    out->group[t] = groupLabel[root];
  }
}

}  // namespace

void checkInput(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) {
    throw std::invalid_argument("decomposeConvex: mesh " + name + " has no triangles");
  }
  const int n = static_cast<int>(mesh.vertices.size());
  for (int i = 0; i < n; ++i) {
    if (!mesh.vertices[i].allFinite()) {
      const Vector3d& v = mesh.vertices[i];
      throw std::invalid_argument("decomposeConvex: mesh " + name + ": vertex " + std::to_string(i) +
                                  " is not finite (" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " +
                                  formatNumber(v.z()) + ")");
    }
  }
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    for (int k : mesh.triangles[t]) {
      if (k < 0 || k >= n) {
        throw std::invalid_argument("decomposeConvex: mesh " + name + ": triangle " + std::to_string(t) +
                                    " has vertex index " + std::to_string(k) + " out of range [0, " +
                                    std::to_string(n) + ")");
      }
    }
  }
}

Eigen::AlignedBox3d usedBox(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box(Vector3d::Constant(kInf), Vector3d::Constant(-kInf));
  for (const auto& tri : mesh.triangles) {
    for (int k : tri) {
      box.min() = box.min().cwiseMin(mesh.vertices[k]);
      box.max() = box.max().cwiseMax(mesh.vertices[k]);
    }
  }
  return box;
}

bool isDegenerate(const Vector3d& a, const Vector3d& b, const Vector3d& c, double diagonal) {
  const double minArea2 = std::pow(tol::kDegenerateRelative * diagonal, 4);
  return 0.25 * (b - a).cross(c - a).squaredNorm() <= minArea2;
}

CleanMesh cleanMesh(const TriangleMesh& mesh) {
  const std::string name = meshName(mesh);
  checkInput(mesh, name);
  CleanMesh out;
  const Eigen::AlignedBox3d box = usedBox(mesh);
  out.diagonal = (box.max() - box.min()).norm();
  weldTriangles(mesh, name, &out);
  const Vector3d origin = keepUsedVertices(&out);

  out.inputVertices = static_cast<int>(out.vertices.size());
  out.inputTriangles = static_cast<int>(out.triangles.size());
  out.holesFilled = fillHoles(&out);
  buildTopology(&out);
  const std::vector<double> volume = orientComponents(&out, origin);
  out.volume = 0.0;
  for (double v : volume) out.volume += v;
  if (!out.closed) out.volume = std::numeric_limits<double>::quiet_NaN();
  groupComponents(&out);
  return out;
}

}  // namespace deepcheck::decomposition::detail
