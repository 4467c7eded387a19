// ConvexPolytope::fromPoints for solids (polytope_internal.h lists the steps): Qhull's hull
// (qhull_hull.h), our own merging of coplanar facets, vertex rings, and rounds of pruning the
// vertices that are not extreme.

#include "polytope_internal.h"

#include "deepcheck/geometry/qhull_hull.h"
#include "deepcheck/geometry/tolerances.h"

#include <iterator>
#include <unordered_map>
#include <utility>

namespace deepcheck::geometry {

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
  const std::vector<Eigen::Vector2d> outline =
      monotoneChain(shadow, [&](const auto& o, const auto& a, const auto& b) { return !(turn(o, a, b) <= 0.0); });
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

namespace {

/// The faces of a solid hull from Qhull's facets: adjacent facets coplanar within kCoplanarAngle
/// and h merged into polygons, then vertices left on two faces only (inside an edge) removed.
/// Loops are counter-clockwise seen from outside and index the builder's points.
class SolidFaces {
 public:
  SolidFaces(const std::vector<Vector3d>& q, double h, const std::string& name) : q_(q), h_(h), name_(name) {}

  std::vector<std::vector<int>> build(const std::vector<int>& ids, double qhullMerge) {
    runQhull(ids, qhullMerge);
    linkEdges();
    mergeCoplanar();
    collectFaces();
    removeEdgeVertices();
    return std::move(faces_);
  }

 private:
  /// A set of facets merged into one face: its vertices (sorted, unique), Newell area and plane.
  struct Group {
    std::vector<int> verts;
    std::vector<int> facets;
    Vector3d area = Vector3d::Zero();
    PlaneFit plane;
  };

  void runQhull(const std::vector<int>& ids, double qhullMerge);
  void linkEdges();
  int twinFacet(int a, int b) const;
  void mergeCoplanar();
  bool mergePass();
  bool tryMerge(int rf, int rg);
  std::vector<int> groupLoop(int r);
  void collectFaces();
  bool dissolveHiddenCorners();
  void countFaces();
  void removeEdgeVertices();
  Vector3d coord(int i) const { return q_[i]; }

  const std::vector<Vector3d>& q_;
  const double h_;
  const std::string& name_;
  std::vector<std::vector<int>> loops_;               // Qhull's facets, indices into q_
  std::unordered_map<std::uint64_t, int> edgeFacet_;  // directed edge -> its facet
  std::vector<Group> group_;                          // by root facet
  std::vector<Vector3d> facetNormal_;                 // each facet's own fitted normal
  UnionFind groups_{0};
  std::vector<std::vector<int>> members_;  // facets of each root
  std::vector<char> dissolved_;            // groups whose merge hid a real corner
  std::vector<std::vector<int>> faces_;
  std::vector<int> faceGroup_;  // the merged group a face comes from, or -1
  std::vector<int> faceCount_;  // faces listing each point
};

// Qhull on the points; loops come back as indices into q_, counter-clockwise (qhullHull).
void SolidFaces::runQhull(const std::vector<int>& ids, double qhullMerge) {
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
  loops_ = qhullHull(kept, options, name_).loops;
  const int numFacets = static_cast<int>(loops_.size());
  group_.assign(numFacets, Group());
  facetNormal_.resize(numFacets);
  auto coord = [&](int i) { return q_[i]; };
  for (int f = 0; f < numFacets; ++f) {
    for (int& v : loops_[f]) v = ids[v];
    Group& g = group_[f];
    g.facets = {f};
    g.verts = loops_[f];
    std::sort(g.verts.begin(), g.verts.end());
    g.area = newellVector(loops_[f], coord);
    g.plane = fitPlane(g.verts, coord, g.area);
    facetNormal_[f] = g.plane.normal;
  }
  groups_ = UnionFind(numFacets);
}

// Half-edges: directed edge (a, b) of a counter-clockwise loop -> its facet.
void SolidFaces::linkEdges() {
  edgeFacet_.reserve(4 * loops_.size());
  for (int f = 0; f < static_cast<int>(loops_.size()); ++f) {
    const auto& l = loops_[f];
    for (std::size_t i = 0; i < l.size(); ++i) {
      if (!edgeFacet_.emplace(edgeKey(l[i], l[(i + 1) % l.size()]), f).second) {
        throwTopologyError(name_, "a directed edge is used twice");
      }
    }
  }
}

int SolidFaces::twinFacet(int a, int b) const {
  const auto it = edgeFacet_.find(edgeKey(b, a));
  if (it == edgeFacet_.end()) throwTopologyError(name_, "an edge has one face only");
  return it->second;
}

double angleBetween(const Vector3d& m, const Vector3d& n) { return std::atan2(m.cross(n).norm(), m.dot(n)); }

// Merges adjacent faces whose normals differ by less than kCoplanarAngle and whose union is
// planar within h_ (Qhull's merging catches most; this enforces our own criterion on the fitted
// planes). The merged normal must stay within kCoplanarAngle of every merged facet's, so chains
// of merges cannot drift. Passes repeat until nothing merges.
void SolidFaces::mergeCoplanar() {
  while (mergePass()) {
  }
  members_.assign(loops_.size(), {});
  for (int f = 0; f < static_cast<int>(loops_.size()); ++f) members_[groups_.find(f)].push_back(f);
  dissolved_.assign(loops_.size(), 0);
}

bool SolidFaces::mergePass() {
  struct Candidate {
    double score;  // angle between the normals: most coplanar first
    int f, g;
  };
  std::vector<Candidate> candidates;
  for (const auto& [key, f] : edgeFacet_) {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    if (a > b) continue;  // each undirected edge once
    const int rf = groups_.find(f);
    const int rg = groups_.find(twinFacet(a, b));
    if (rf == rg) continue;
    const double angle = angleBetween(group_[rf].plane.normal, group_[rg].plane.normal);
    if (angle < tol::kCoplanarAngle) candidates.push_back({angle, rf, rg});
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& l, const Candidate& r) {
    return l.score < r.score || (l.score == r.score && (l.f < r.f || (l.f == r.f && l.g < r.g)));
  });
  bool merged = false;
  for (const Candidate& c : candidates) {
    const int rf = groups_.find(c.f);
    const int rg = groups_.find(c.g);
    if (rf != rg && tryMerge(rf, rg)) merged = true;
  }
  return merged;
}

// Merges groups rf and rg (roots) when the union passes the tests of mergeCoplanar.
bool SolidFaces::tryMerge(int rf, int rg) {
  if (!(angleBetween(group_[rf].plane.normal, group_[rg].plane.normal) < tol::kCoplanarAngle)) {
    return false;
  }
  auto coord = [&](int i) { return q_[i]; };
  Group u;
  std::merge(group_[rf].verts.begin(), group_[rf].verts.end(), group_[rg].verts.begin(), group_[rg].verts.end(),
             std::back_inserter(u.verts));
  u.verts.erase(std::unique(u.verts.begin(), u.verts.end()), u.verts.end());
  u.area = group_[rf].area + group_[rg].area;
  u.plane = fitPlane(u.verts, coord, u.area);
  if (!(u.plane.band <= h_)) return false;
  u.facets = group_[rf].facets;
  u.facets.insert(u.facets.end(), group_[rg].facets.begin(), group_[rg].facets.end());
  for (int f : u.facets) {
    if (!(angleBetween(facetNormal_[f], u.plane.normal) < tol::kCoplanarAngle)) return false;
  }
  groups_.unite(rf, rg);
  group_[rf] = std::move(u);
  group_[rg] = Group();
  return true;
}

// The loop of merged group r: its boundary half-edges, chained. Empty when the boundary is not
// one simple loop (possible only at tolerance level): the group is then left unmerged.
std::vector<int> SolidFaces::groupLoop(int r) {
  std::unordered_map<int, int> nextOf;
  bool simple = true;
  int start = std::numeric_limits<int>::max();
  for (int f : members_[r]) {
    const auto& l = loops_[f];
    for (std::size_t i = 0; i < l.size(); ++i) {
      const int a = l[i];
      const int b = l[(i + 1) % l.size()];
      if (groups_.find(twinFacet(a, b)) == r) continue;  // interior edge
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
}

void SolidFaces::countFaces() {
  faceCount_.assign(q_.size(), 0);
  for (const auto& l : faces_) {
    for (int v : l) ++faceCount_[v];
  }
}

// Faces: the loops of the merged groups (those not dissolved) and the facets of the others, until
// no merge hides a corner.
void SolidFaces::collectFaces() {
  do {
    faces_.clear();
    faceGroup_.clear();
    for (int r = 0; r < static_cast<int>(members_.size()); ++r) {
      if (members_[r].empty()) continue;
      std::vector<int> loop;
      if (members_[r].size() > 1 && !dissolved_[r]) loop = groupLoop(r);
      if (!loop.empty()) {
        faces_.push_back(std::move(loop));
        faceGroup_.push_back(r);
      } else {
        for (int f : members_[r]) {
          faces_.push_back(loops_[f]);
          faceGroup_.push_back(-1);
        }
      }
    }
    countFaces();
  } while (dissolveHiddenCorners());
}

// A vertex left on two faces only must lie on the straight edge between its loop neighbours
// (within h_), else it is a real corner that a merge hid (thin sets): such merges are undone.
// Returns true when one was.
bool SolidFaces::dissolveHiddenCorners() {
  bool redo = false;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const auto& l = faces_[f];
    const std::size_t k = l.size();
    for (std::size_t i = 0; i < k; ++i) {
      if (faceCount_[l[i]] != 2) continue;
      const Vector3d a = q_[l[(i + k - 1) % k]];
      const Vector3d chord = q_[l[(i + 1) % k]] - a;
      const Vector3d x = q_[l[i]] - a;
      const double t = std::clamp(x.dot(chord) / chord.squaredNorm(), 0.0, 1.0);
      if ((x - t * chord).norm() <= h_) continue;
      for (std::size_t g = 0; g < faces_.size(); ++g) {
        if (faceGroup_[g] >= 0 && std::find(faces_[g].begin(), faces_[g].end(), l[i]) != faces_[g].end()) {
          dissolved_[faceGroup_[g]] = 1;
          redo = true;
        }
      }
    }
  }
  return redo;
}

// Removes vertices on only two faces (inside an edge: not extreme points); faces left with fewer
// than three vertices vanish (their two half-edges' twins then pair up).
void SolidFaces::removeEdgeVertices() {
  for (bool changed = true; changed;) {
    changed = false;
    countFaces();
    for (auto& l : faces_) {
      const std::size_t before = l.size();
      l.erase(std::remove_if(l.begin(), l.end(), [&](int v) { return faceCount_[v] == 2; }), l.end());
      changed = changed || l.size() != before;
    }
    const std::size_t before = faces_.size();
    faces_.erase(std::remove_if(faces_.begin(), faces_.end(), [](const std::vector<int>& l) { return l.size() < 3; }),
                 faces_.end());
    changed = changed || faces_.size() != before;
  }
}

}  // namespace

// The hull of the points `ids` (indices into points_); reports its vertices' indices and the
// vertices found redundant (see makeSolid).
ConvexPolytope PolytopeBuilder::makePolyhedron(const std::vector<int>& ids, double qhullMerge,
                                               std::vector<int>* vertexIds, std::vector<int>* redundant) const {
  const std::vector<std::vector<int>> faces = SolidFaces(q_, h_, name_).build(ids, qhullMerge);
  ConvexPolytope p = assembleSolid(faces, vertexIds);
  buildRings(p);
  findRedundant(p, *vertexIds, redundant);
  p.flatTol_ = h_;
  p.finish();
  return p;
}

// Vertices in input order (vertexIds: their indices into points_) and faces with fitted normals.
ConvexPolytope PolytopeBuilder::assembleSolid(const std::vector<std::vector<int>>& faces,
                                              std::vector<int>* vertexIds) const {
  const int numPoints = static_cast<int>(points_.size());
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
  if (p.vertices_.size() < 4 || faces.size() < 4) topologyError("fewer than four vertices or faces");
  p.faceStart_.push_back(0);
  for (const auto& l : faces) {
    const Vector3d n = fitNormal(l, [&](int i) { return q_[i]; });
    if (!(n.norm() > 0.0)) topologyError("a face has zero area");
    p.faceNormals_.push_back(n);
    for (int v : l) p.faceVerts_.push_back(compact[v]);
    p.faceStart_.push_back(static_cast<int>(p.faceVerts_.size()));
  }
  return p;
}

// Vertex rings. For ring face F_j: nbr_j = F_j's successor of v, nbr_{j+1} = F_j's predecessor
// of v, and F_{j+1} is the face whose successor of v is nbr_{j+1}.
void PolytopeBuilder::buildRings(ConvexPolytope& p) const {
  struct Incidence {
    int face, next, prev;
  };
  std::vector<std::vector<Incidence>> around(p.numVertices());
  for (int f = 0; f < p.numFaces(); ++f) {
    const int s = p.faceStart_[f];
    const int k = p.faceStart_[f + 1] - s;
    for (int i = 0; i < k; ++i) {
      around[p.faceVerts_[s + i]].push_back({f, p.faceVerts_[s + (i + 1) % k], p.faceVerts_[s + (i + k - 1) % k]});
    }
  }
  p.adjStart_.push_back(0);
  for (int v = 0; v < p.numVertices(); ++v) {
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
}

// Redundant vertices: at a face corner that sticks out of the chord of its two neighbours by no
// more than h_ (straight or reflex). Most redundant first, no two adjacent.
void PolytopeBuilder::findRedundant(const ConvexPolytope& p, const std::vector<int>& vertexIds,
                                    std::vector<int>* redundant) const {
  const int numVerts = p.numVertices();
  std::vector<double> stickOut(numVerts, std::numeric_limits<double>::infinity());
  for (int f = 0; f < p.numFaces(); ++f) {
    const int s = p.faceStart_[f];
    const int k = p.faceStart_[f + 1] - s;
    const Vector3d& n = p.faceNormals_[f];
    for (int i = 0; i < k; ++i) {
      const int v = p.faceVerts_[s + i];
      const Vector3d a = q_[vertexIds[p.faceVerts_[s + (i + k - 1) % k]]];
      const Vector3d chord = q_[vertexIds[p.faceVerts_[s + (i + 1) % k]]] - a;
      const Vector3d x = q_[vertexIds[v]] - a;
      const double along = x.dot(chord) / chord.squaredNorm();
      const double out = chord.cross(n).dot(x) / chord.norm();
      // A corner within h_ of the chord line but beyond its ends is a spike (a sliver's end),
      // which is extreme; a clearly reflex corner is never extreme in its face.
      if (out >= -h_ && !(along >= 0.0 && along <= 1.0)) continue;
      stickOut[v] = std::min(stickOut[v], out);
    }
  }
  std::vector<std::pair<double, int>> candidates;
  for (int v = 0; v < numVerts; ++v) {
    if (!(stickOut[v] > h_)) candidates.emplace_back(stickOut[v], v);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> blocked(numVerts, 0);
  for (const auto& [out, v] : candidates) {
    if (blocked[v]) continue;
    redundant->push_back(vertexIds[v]);
    blocked[v] = 1;
    for (int k = p.adjStart_[v]; k < p.adjStart_[v + 1]; ++k) blocked[p.adjVerts_[k]] = 1;
  }
}

}  // namespace deepcheck::geometry
