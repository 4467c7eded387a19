// Parts of the decomposition: clipping to a cell, cell corners, components (decomposer.h).

#include "decomposer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_set>
#include <unordered_map>

namespace deepcheck::decomposition::detail {

std::vector<PartPolygon> Decomposer::clip(const std::vector<PartPolygon>& polygons, const Halfspace& keep) const {
  std::vector<PartPolygon> out;
  out.reserve(polygons.size());
  const double minArea = std::pow(tol::kDegenerateRelative * diagonal_, 2);
  std::vector<Vector3d> clipped;
  const double onPlane = tol::kOnPlaneRelative * diagonal_;
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
  const double tolerance = tol::kOnPlaneRelative * diagonal_;
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

namespace {

/// Whether the segment a-b meets the cell (the intersection of the half-spaces).
bool edgeMeetsCell(const std::vector<Halfspace>& halfspaces, const Vector3d& a, const Vector3d& b) {
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
}

}  // namespace

void Decomposer::joinAcrossEdges(const std::unordered_map<int, int>& node, const std::vector<int>& sources,
                                 const std::vector<Halfspace>& halfspaces, std::vector<int>* parent) const {
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
          meets = edgeMeetsCell(halfspaces, mesh_.vertices[tri[e]], mesh_.vertices[tri[(e + 1) % 3]]);
          checked = true;
        }
        if (meets) unite(*parent, static_cast<int>(i), it->second);
      }
    }
  }
}

void Decomposer::joinThroughCutFaces(const std::vector<PartPolygon>& polygons, const std::vector<CellSide>& cell,
                                     const std::unordered_map<int, int>& node, const std::vector<int>& sources,
                                     const std::vector<Halfspace>& halfspaces, std::vector<int>* parent) const {
  std::map<std::pair<int, int>, int> regionNode;
  auto join = [&](int sourceNode, int plane, int region) {
    auto [it, inserted] = regionNode.emplace(std::make_pair(plane, region), static_cast<int>(parent->size()));
    if (inserted) parent->push_back(it->second);
    unite(*parent, sourceNode, it->second);
  };
  const double onPlane = tol::kOnPlaneRelative * diagonal_;
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
        if (region >= 0) join(node.at(polygon.source), cell[c].plane, region);
        break;
      }
    }
  }
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
  joinAcrossEdges(node, sources, halfspaces, &parent);
  joinThroughCutFaces(polygons, cell, node, sources, halfspaces, &parent);
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
  assignCellCorners(cell, halfspaces, &out);
  return out;
}

std::vector<int> Decomposer::cornerOwners(const CellCorner& corner, const std::vector<Halfspace>& halfspaces,
                                          const std::vector<Component>& out,
                                          const std::vector<char>& touchesCell) const {
  Vector3d inward = Vector3d::Zero();
  for (int c : corner.planes) inward -= halfspaces[c].normal;
  const Vector3d axis = inward.normalized();
  std::vector<int> owners;
  for (int attempt = 0; owners.empty() && attempt < tol::kCornerRays && axis.allFinite(); ++attempt) {
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
          const double t =
              detail::rayTriangle(corner.point, dir, polygon.corners[0], polygon.corners[k], polygon.corners[k + 1]);
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
  return owners;
}

void Decomposer::assignCellCorners(const std::vector<CellSide>& cell, const std::vector<Halfspace>& halfspaces,
                                   std::vector<Component>* out) const {
  // Cell corners inside the solid: the solid's cut faces end there, so the hull of the component
  // whose solid holds the corner must include it. That component is found by casting a ray from
  // the corner into the cell: the ray runs inside that solid until it meets the solid's surface,
  // and the first polygon it meets is that component's. A component that touches no cell plane
  // may be a void inside the solid (an inner boundary): then the first component touching the
  // cell's planes along the ray gets the corner too. A corner whose rays all leave the cell first
  // goes to every component (safe).
  const double onPlane = tol::kOnPlaneRelative * diagonal_;
  std::vector<char> touchesCell(out->size(), 0);
  for (std::size_t i = 0; i < out->size(); ++i) {
    for (const PartPolygon& polygon : (*out)[i].polygons) {
      for (const Vector3d& p : polygon.corners) {
        for (const Halfspace& h : halfspaces)
          touchesCell[i] = touchesCell[i] || std::abs(h.signedDistance(p)) <= onPlane;
      }
    }
  }
  for (const CellCorner& corner : solidCellCorners(cell)) {
    std::vector<int> owners = cornerOwners(corner, halfspaces, *out, touchesCell);
    // No owner found: every component gets the corner (safe), but only for a closed mesh. An open
    // mesh has no well-defined solid (its inside test is fuzzy near holes), so there only corners
    // with an owner are added; its surface is covered either way.
    if (owners.empty() && mesh_.closed) {
      for (int i = 0; i < static_cast<int>(out->size()); ++i) owners.push_back(i);
    }
    for (int i : owners) (*out)[i].cellCorners.push_back(corner.point);
  }
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
  const Concavity c =
      measureConcavity(part.hull, target, tol::kPartSamples, Extra::Dense, nextSeed(), kInf, diagonal_, hint);
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
  if (part->hullConcavity > target_ || static_cast<int>(part->hull.vertices.size()) <= params_.maxVerticesPerPiece) {
    return;
  }
  part->finalHull = detail::reduceHullVertices(part->hull, params_.maxVerticesPerPiece);
  Target target;
  target.mesh = &meshBvh_;
  addCaps(*part, &target.caps);
  part->concavity =
      measureConcavity(part->finalHull, target, tol::kPartSamples, Extra::Dense, nextSeed(), kInf, diagonal_).value;
  part->reductionLimited = part->concavity > target_;
}

}  // namespace deepcheck::decomposition::detail
