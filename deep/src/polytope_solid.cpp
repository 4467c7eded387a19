// ConvexPolytope::fromPoints for solids (polytope_internal.h lists the steps): Qhull's hull
// (qhull_hull.h), our own merging of coplanar facets, vertex rings, and rounds of pruning the
// vertices that are not extreme.

#include "polytope_internal.h"

#include "deepcheck/deep/qhull_hull.h"
#include "deepcheck/deep/tolerances.h"

#include <iterator>
#include <unordered_map>
#include <utility>

namespace deepcheck::deep {

using namespace detail;

namespace {

/// Solids thinner than kQhullMergeMinThickness * h (h the flatness tolerance; a factor, not a
/// tolerance) are built without Qhull's tolerance-sized facet merging.
constexpr double kQhullMergeMinThickness = 1000.0;
/// At most this many rounds of dropping redundant vertices and rebuilding (see makeSolid).
constexpr int kMaxPruneRounds = 8;

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) {
    for (int i = 0; i < n; ++i) parent_[i] = i;
  }
  int find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(int root, int other) { parent_[other] = root; }

 private:
  std::vector<int> parent_;
};

}  // namespace


// The solid hull, in rounds. Qhull merging facets within h_ gives clean faces on noisy coplanar
// input; on sets only tens of h_ thick its merge thresholds (several h_) reach across the whole
// thickness and it can fail or collapse the rim, so thin sets, and sets where the merged hull
// fails its check, are built with round-off-level merging (C-0) and our own merging only.
// Merging within a tolerance can leave a vertex that is not an extreme point (it sits at a face
// corner that is straight or reflex within h_: the remains of noise, or of a sliver along an
// edge). Hill climbing can stop at such a vertex far from the maximum, and a sliver's normal is
// arbitrary, so these vertices are dropped (an independent set at a time, so each one stays
// within h_ of the hull of its kept neighbours) and the hull is rebuilt from the remaining
// vertices, until none is left. The result is the last round's hull that holds all input points
// within hullTolerance() and is locally convex (see covers).
ConvexPolytope PolytopeBuilder::makeSolid(double thickness) const {
  const bool merge = thickness >= kQhullMergeMinThickness * h_;
  SolidAttempt attempt = pruneRounds(merge);
  if (attempt.clean || !merge) return std::move(attempt.hull);
  SolidAttempt conservative = pruneRounds(false);
  if (conservative.clean || !attempt.covers) return std::move(conservative.hull);
  return std::move(attempt.hull);
}

// Rounds of hull building and pruning, with or without Qhull's merging (see makeSolid). Clean
// when the hull returned holds all points (covers) and has no redundant vertex left.
PolytopeBuilder::SolidAttempt PolytopeBuilder::pruneRounds(bool merge) const {
  std::vector<int> ids = ids_;
  SolidAttempt best;  // the last hull that passed the check
  SolidAttempt last;
  for (int round = 0; round < kMaxPruneRounds; ++round) {
    std::vector<int> vertexIds;
    std::vector<int> redundant;
    try {
      last.hull = makePolyhedron(ids, merge ? h_ : 0.0, &vertexIds, &redundant);
      last.covers = covers(last.hull, vertexIds);
      last.clean = last.covers && redundant.empty() && last.hull.checkInvariants(false).empty();
    } catch (const std::runtime_error&) {
      if (round == 0 && !merge) throw;
      break;  // Qhull's merging failed, or pruned down to a degenerate set
    }
    if (last.covers) best = last;
    if (redundant.empty() || (merge && !last.covers)) break;
    std::sort(redundant.begin(), redundant.end());
    ids.clear();
    for (int i : vertexIds) {
      if (!std::binary_search(redundant.begin(), redundant.end(), i)) ids.push_back(i);
    }
  }
  return best.covers ? best : last;
}

// True when the hull is locally convex (every vertex's neighbours are inside its ring faces'
// planes) and every input point is inside every face plane, within hullTolerance(). A closed,
// locally convex surface is convex, so the hull's own vertices (vertexIds) need no plane test.
bool PolytopeBuilder::covers(const ConvexPolytope& p, const std::vector<int>& vertexIds) const {
  const double tol = p.hullTolerance();
  const int nf = p.numFaces();
  std::vector<double> localOffset(nf);
  double inRadius = std::numeric_limits<double>::infinity();
  for (int f = 0; f < nf; ++f) {
    localOffset[f] = p.faceOffset(f) - p.faceNormal(f).dot(p.center());
    inRadius = std::min(inRadius, localOffset[f]);
  }
  for (int v = 0; v < p.numVertices(); ++v) {
    for (int f : p.vertexFaces(v)) {
      for (int u : p.neighbors(v)) {
        if (p.faceNormal(f).dot(p.localVertex(u)) - localOffset[f] > tol) return false;
      }
    }
  }
  // Face planes of a thin hull are nearly parallel and cannot see a point missed in its plane:
  // every point must also be inside the hull's shadow on the plane of the classification (the
  // 2-d convex hull of the projected vertices), within tol.
  const Vector3d e0 = lineDir_;
  const Vector3d e1 = planeNormal_.cross(lineDir_);
  std::vector<Eigen::Vector2d> shadow;
  for (int v = 0; v < p.numVertices(); ++v) {
    shadow.emplace_back(e0.dot(p.localVertex(v)), e1.dot(p.localVertex(v)));
  }
  std::sort(shadow.begin(), shadow.end(), [](const Eigen::Vector2d& l, const Eigen::Vector2d& r) {
    return l.x() < r.x() || (l.x() == r.x() && l.y() < r.y());
  });
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  const std::vector<Eigen::Vector2d> outline = monotoneChain(
      shadow, [&](const auto& o, const auto& a, const auto& b) { return !(turn(o, a, b) <= 0.0); });
  for (const Vector3d& point : points_) {
    const Vector3d x = point - p.center();
    const Eigen::Vector2d y(e0.dot(x), e1.dot(x));
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const Eigen::Vector2d& a = outline[i];
      const Eigen::Vector2d& b = outline[(i + 1) % outline.size()];
      if (turn(a, b, y) < -tol * (b - a).norm()) return false;
    }
  }
  std::vector<char> isVertex(points_.size(), 0);
  for (int i : vertexIds) isVertex[i] = 1;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vector3d x = points_[i] - p.center();
    if (isVertex[i] || x.norm() <= inRadius - tol) continue;  // a vertex, or in the inscribed ball
    for (int f = 0; f < nf; ++f) {
      if (p.faceNormal(f).dot(x) - localOffset[f] > tol) return false;
    }
  }
  return true;
}

// The hull of the points `ids` (indices into points_); reports its vertices' indices and the
// vertices found redundant (see makeSolid).
ConvexPolytope PolytopeBuilder::makePolyhedron(const std::vector<int>& ids, double qhullMerge,
                                               std::vector<int>* vertexIds,
                                               std::vector<int>* redundant) const {
  // --- Qhull on the points; loops come back as indices into points_.
  std::vector<Vector3d> kept;
  kept.reserve(ids.size());
  for (int i : ids) kept.push_back(q_[i]);
  // Qs: search all points for the initial simplex (robust on thin sets). C-m: pre-merge facets
  // whose centrum is within m of a neighbour's plane, so coplanar triangles come out as one
  // polygonal facet and, with m our flatness tolerance, no sliver thinner than m survives (C-0,
  // Qhull's default, merges at round-off level only: noisy coplanar input then leaves facets
  // whose normals are set by the noise).
  QhullOptions options;
  options.mergeDistance = qhullMerge;
  QhullHull qf = qhullHull(kept, options, name_);
  auto coord = [&](int i) { return q_[i]; };
  std::vector<std::vector<int>>& loops = qf.loops;
  const int numFacets = static_cast<int>(loops.size());
  std::vector<Vector3d> area(numFacets);
  for (int f = 0; f < numFacets; ++f) {
    for (int& v : loops[f]) v = ids[v];
    area[f] = newellVector(loops[f], coord);  // loops are counter-clockwise (qhullHull)
  }

  // --- Half-edges: directed edge (a, b) of a counter-clockwise loop -> its facet.
  std::unordered_map<std::uint64_t, int> edgeFacet;
  edgeFacet.reserve(4 * static_cast<std::size_t>(numFacets));
  for (int f = 0; f < numFacets; ++f) {
    const auto& l = loops[f];
    for (std::size_t i = 0; i < l.size(); ++i) {
      if (!edgeFacet.emplace(edgeKey(l[i], l[(i + 1) % l.size()]), f).second) {
        topologyError("a directed edge is used twice");
      }
    }
  }
  auto twinFacet = [&](int a, int b) {
    const auto it = edgeFacet.find(edgeKey(b, a));
    if (it == edgeFacet.end()) topologyError("an edge has one face only");
    return it->second;
  };

  // --- Merge adjacent faces whose normals differ by less than kCoplanarAngle and whose union is
  // planar within h_ (Qhull's merging catches most; this enforces our own criterion on the
  // fitted planes). The merged normal must stay within kCoplanarAngle of every merged facet's,
  // so chains of merges cannot drift. Passes repeat until nothing merges.
  struct Group {
    std::vector<int> verts;  // sorted, unique
    std::vector<int> facets;
    Vector3d area = Vector3d::Zero();
    PlaneFit plane;
  };
  std::vector<Group> group(numFacets);
  for (int f = 0; f < numFacets; ++f) {
    group[f].facets = {f};
    group[f].verts = loops[f];
    std::sort(group[f].verts.begin(), group[f].verts.end());
    group[f].area = area[f];
    group[f].plane = fitPlane(group[f].verts, coord, area[f]);
  }
  auto angleBetween = [](const Vector3d& m, const Vector3d& n) {
    return std::atan2(m.cross(n).norm(), m.dot(n));
  };
  std::vector<Vector3d> facetNormal(numFacets);
  for (int f = 0; f < numFacets; ++f) facetNormal[f] = group[f].plane.normal;
  UnionFind groups(numFacets);
  for (bool merged = true; merged;) {
    merged = false;
    struct Candidate {
      double score;  // angle between the normals: most coplanar first
      int f, g;
    };
    std::vector<Candidate> candidates;
    for (const auto& [key, f] : edgeFacet) {
      const int a = static_cast<int>(key >> 32);
      const int b = static_cast<int>(key & 0xffffffffu);
      if (a > b) continue;  // each undirected edge once
      const int rf = groups.find(f);
      const int rg = groups.find(twinFacet(a, b));
      if (rf == rg) continue;
      const double angle = angleBetween(group[rf].plane.normal, group[rg].plane.normal);
      if (angle < tol::kCoplanarAngle) candidates.push_back({angle, rf, rg});
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& l, const Candidate& r) {
      return l.score < r.score || (l.score == r.score && (l.f < r.f || (l.f == r.f && l.g < r.g)));
    });
    for (const Candidate& c : candidates) {
      const int rf = groups.find(c.f);
      const int rg = groups.find(c.g);
      if (rf == rg) continue;
      if (!(angleBetween(group[rf].plane.normal, group[rg].plane.normal) < tol::kCoplanarAngle)) {
        continue;
      }
      Group u;
      std::merge(group[rf].verts.begin(), group[rf].verts.end(), group[rg].verts.begin(),
                 group[rg].verts.end(), std::back_inserter(u.verts));
      u.verts.erase(std::unique(u.verts.begin(), u.verts.end()), u.verts.end());
      u.area = group[rf].area + group[rg].area;
      u.plane = fitPlane(u.verts, coord, u.area);
      if (!(u.plane.band <= h_)) continue;
      u.facets = group[rf].facets;
      u.facets.insert(u.facets.end(), group[rg].facets.begin(), group[rg].facets.end());
      bool drift = false;
      for (int f : u.facets) {
        drift = drift || !(angleBetween(facetNormal[f], u.plane.normal) < tol::kCoplanarAngle);
      }
      if (drift) continue;
      groups.unite(rf, rg);
      group[rf] = std::move(u);
      group[rg] = Group();
      merged = true;
    }
  }

  // --- Loops of merged faces: the boundary half-edges of the group, chained. A group whose
  // boundary is not one simple loop (possible only at tolerance level) is left unmerged.
  std::vector<std::vector<int>> members(numFacets);
  for (int f = 0; f < numFacets; ++f) members[groups.find(f)].push_back(f);
  std::vector<char> dissolved(numFacets, 0);
  auto groupLoop = [&](int r) {
    std::unordered_map<int, int> nextOf;
    bool simple = true;
    int start = std::numeric_limits<int>::max();
    for (int f : members[r]) {
      const auto& l = loops[f];
      for (std::size_t i = 0; i < l.size(); ++i) {
        const int a = l[i];
        const int b = l[(i + 1) % l.size()];
        if (groups.find(twinFacet(a, b)) == r) continue;  // interior edge
        if (!nextOf.emplace(a, b).second) simple = false;
        start = std::min(start, a);
      }
    }
    std::vector<int> loop;
    if (simple && !nextOf.empty()) {
      int v = start;
      do {
        loop.push_back(v);
        const auto it = nextOf.find(v);
        if (it == nextOf.end()) break;
        v = it->second;
      } while (v != start && loop.size() <= nextOf.size());
      simple = v == start && loop.size() == nextOf.size();
    }
    if (!(simple && loop.size() >= 3)) loop.clear();
    return loop;
  };
  const int numPoints = static_cast<int>(points_.size());
  std::vector<int> faceCount(numPoints, 0);
  std::vector<std::vector<int>> faces;
  auto countFaces = [&] {  // faceCount[v]: the faces listing v
    std::fill(faceCount.begin(), faceCount.end(), 0);
    for (const auto& l : faces) {
      for (int v : l) ++faceCount[v];
    }
  };
  std::vector<int> faceGroup;  // the merged group a face comes from, or -1
  // A vertex left on two faces only must lie on the straight edge between its loop neighbours
  // (within h_), else it is a real corner that a merge hid (thin sets): such merges are undone.
  for (bool redo = true; redo;) {
    redo = false;
    faces.clear();
    faceGroup.clear();
    for (int r = 0; r < numFacets; ++r) {
      if (members[r].empty()) continue;
      std::vector<int> loop;
      if (members[r].size() > 1 && !dissolved[r]) loop = groupLoop(r);
      if (!loop.empty()) {
        faces.push_back(std::move(loop));
        faceGroup.push_back(r);
      } else {
        for (int f : members[r]) {
          faces.push_back(loops[f]);
          faceGroup.push_back(-1);
        }
      }
    }
    countFaces();
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto& l = faces[f];
      const std::size_t k = l.size();
      for (std::size_t i = 0; i < k; ++i) {
        if (faceCount[l[i]] != 2) continue;
        const Vector3d a = q_[l[(i + k - 1) % k]];
        const Vector3d chord = q_[l[(i + 1) % k]] - a;
        const Vector3d x = q_[l[i]] - a;
        const double t = std::clamp(x.dot(chord) / chord.squaredNorm(), 0.0, 1.0);
        if ((x - t * chord).norm() <= h_) continue;
        for (std::size_t g = 0; g < faces.size(); ++g) {
          if (faceGroup[g] >= 0 &&
              std::find(faces[g].begin(), faces[g].end(), l[i]) != faces[g].end()) {
            dissolved[faceGroup[g]] = 1;
            redo = true;
          }
        }
      }
    }
  }

  // --- Remove vertices on only two faces (inside an edge: not extreme points); faces left with
  // fewer than three vertices vanish (their two half-edges' twins then pair up).
  for (bool changed = true; changed;) {
    changed = false;
    countFaces();
    for (auto& l : faces) {
      const std::size_t before = l.size();
      l.erase(std::remove_if(l.begin(), l.end(), [&](int v) { return faceCount[v] == 2; }),
              l.end());
      changed = changed || l.size() != before;
    }
    const std::size_t before = faces.size();
    faces.erase(std::remove_if(faces.begin(), faces.end(),
                               [](const std::vector<int>& l) { return l.size() < 3; }),
                faces.end());
    changed = changed || faces.size() != before;
  }

  // --- Final numbering: vertices in input order.
  std::vector<int> compact(numPoints, -1);
  for (const auto& l : faces) {
    for (int v : l) compact[v] = 0;
  }
  ConvexPolytope p;
  p.kind_ = PolytopeKind::Polyhedron;
  for (int i = 0; i < numPoints; ++i) {
    if (compact[i] < 0) continue;
    compact[i] = static_cast<int>(p.vertices_.size());
    p.vertices_.push_back(points_[i]);
    vertexIds->push_back(i);
  }
  const int numVerts = static_cast<int>(p.vertices_.size());
  const int numFaces = static_cast<int>(faces.size());
  if (numVerts < 4 || numFaces < 4) topologyError("fewer than four vertices or faces");
  p.faceStart_.push_back(0);
  for (const auto& l : faces) {
    const Vector3d n = fitNormal(l, coord);
    if (!(n.norm() > 0.0)) topologyError("a face has zero area");
    p.faceNormals_.push_back(n);
    for (int v : l) p.faceVerts_.push_back(compact[v]);
    p.faceStart_.push_back(static_cast<int>(p.faceVerts_.size()));
  }

  // --- Vertex rings. For ring face F_j: nbr_j = F_j's successor of v, nbr_{j+1} = F_j's
  // predecessor of v, and F_{j+1} is the face whose successor of v is nbr_{j+1}.
  struct Incidence {
    int face, next, prev;
  };
  std::vector<std::vector<Incidence>> around(numVerts);
  for (int f = 0; f < numFaces; ++f) {
    const int s = p.faceStart_[f];
    const int k = p.faceStart_[f + 1] - s;
    for (int i = 0; i < k; ++i) {
      around[p.faceVerts_[s + i]].push_back(
          {f, p.faceVerts_[s + (i + 1) % k], p.faceVerts_[s + (i + k - 1) % k]});
    }
  }
  p.adjStart_.push_back(0);
  for (int v = 0; v < numVerts; ++v) {
    const auto& inc = around[v];
    const int k = static_cast<int>(inc.size());
    if (k < 3) topologyError("a vertex on fewer than three faces");
    int cur = 0;
    for (int j = 0; j < k; ++j) {
      p.adjFaces_.push_back(inc[cur].face);
      p.adjVerts_.push_back(inc[cur].next);
      const int wanted = inc[cur].prev;
      int found = -1;
      for (int t = 0; t < k; ++t) {
        if (inc[t].next == wanted) found = t;
      }
      if (found < 0) topologyError("an open vertex ring");
      cur = found;
    }
    if (cur != 0) topologyError("a vertex ring that does not close");
    p.adjStart_.push_back(static_cast<int>(p.adjVerts_.size()));
  }

  // --- Redundant vertices: at a face corner that sticks out of the chord of its two neighbours
  // by no more than h_ (straight or reflex). Most redundant first, no two adjacent.
  std::vector<std::pair<double, int>> candidates;
  std::vector<double> stickOut(numVerts, std::numeric_limits<double>::infinity());
  for (int f = 0; f < numFaces; ++f) {
    const int s = p.faceStart_[f];
    const int k = p.faceStart_[f + 1] - s;
    const Vector3d& n = p.faceNormals_[f];
    for (int i = 0; i < k; ++i) {
      const int prev = p.faceVerts_[s + (i + k - 1) % k];
      const int v = p.faceVerts_[s + i];
      const int next = p.faceVerts_[s + (i + 1) % k];
      const Vector3d a = q_[vertexIds->at(prev)];
      const Vector3d chord = q_[vertexIds->at(next)] - a;
      const Vector3d x = q_[vertexIds->at(v)] - a;
      const double along = x.dot(chord) / chord.squaredNorm();
      const double out = chord.cross(n).dot(x) / chord.norm();
      // A corner within h_ of the chord line but beyond its ends is a spike (a sliver's end),
      // which is extreme; a clearly reflex corner is never extreme in its face.
      if (out >= -h_ && !(along >= 0.0 && along <= 1.0)) continue;
      stickOut[v] = std::min(stickOut[v], out);
    }
  }
  for (int v = 0; v < numVerts; ++v) {
    if (!(stickOut[v] > h_)) candidates.emplace_back(stickOut[v], v);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> blocked(numVerts, 0);
  for (const auto& [out, v] : candidates) {
    if (blocked[v]) continue;
    redundant->push_back(vertexIds->at(v));
    blocked[v] = 1;
    for (int k = p.adjStart_[v]; k < p.adjStart_[v + 1]; ++k) blocked[p.adjVerts_[k]] = 1;
  }

  p.flatTol_ = h_;
  p.finish();
  return p;
}

}  // namespace deepcheck::deep
