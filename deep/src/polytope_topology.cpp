// The invariants of a ConvexPolytope (ConvexPolytope::validate): counts, face loops, convexity,
// vertex rings and the Gauss-map order of their normals.

#include "polytope_internal.h"

#include "deepcheck/deep/tolerances.h"

#include <sstream>
#include <unordered_map>

namespace deepcheck::deep {

using namespace detail;

std::string ConvexPolytope::validate() const { return checkInvariants(true); }

std::string ConvexPolytope::checkInvariants(bool globalConvexity) const {
  std::ostringstream out;
  auto fail = [&out](const auto&... parts) {
    (out << ... << parts);
    return out.str();
  };
  const int nv = numVertices();
  const int nf = numFaces();
  if (nv < 1) return fail("no vertices");
  if (static_cast<int>(local_.size()) != nv || static_cast<int>(adjStart_.size()) != nv + 1 ||
      static_cast<int>(faceStart_.size()) != nf + 1 ||
      static_cast<int>(faceOffsets_.size()) != nf) {
    return fail("array sizes do not match the counts");
  }
  if (adjStart_[nv] != static_cast<int>(adjVerts_.size())) return fail("adjacency size");
  if (!adjFaces_.empty() && adjFaces_.size() != adjVerts_.size()) return fail("ring size");
  for (int v = 0; v < nv; ++v) {
    if (!vertices_[v].allFinite()) return fail("vertex ", v, " is not finite");
  }
  if (!(lengthScale_ > 0.0)) return fail("lengthScale is not positive");

  switch (kind_) {
    case PolytopeKind::Point:
      if (nv != 1 || nf != 0 || !adjVerts_.empty()) return fail("a Point has 1 vertex, no faces");
      return "";
    case PolytopeKind::Segment:
      if (nv != 2 || nf != 0) return fail("a Segment has 2 vertices, no faces");
      if (vertices_[0] == vertices_[1]) return fail("Segment vertices coincide");
      if (neighbors(0).size() != 1 || neighbors(0)[0] != 1 || neighbors(1).size() != 1 ||
          neighbors(1)[0] != 0) {
        return fail("Segment vertices must be each other's only neighbour");
      }
      return "";
    case PolytopeKind::Polygon:
      if (nv < 3 || nf != 2) return fail("a Polygon has >= 3 vertices and 2 faces");
      if ((faceNormals_[0] + faceNormals_[1]).norm() > 1e-12) {
        return fail("Polygon face normals are not opposite");
      }
      for (int i = 0; i < nv; ++i) {
        if (faceVertices(0)[i] != i || faceVertices(1)[i] != nv - 1 - i) {
          return fail("Polygon faces must list 0..k-1 and k-1..0");
        }
      }
      break;
    case PolytopeKind::Polyhedron:
      if (nv < 4 || nf < 4) return fail("a Polyhedron has >= 4 vertices and faces");
      break;
  }

  const double tol = hullTolerance();
  const bool solid = kind_ == PolytopeKind::Polyhedron;
  // Faces: size, unit normal, planarity, counter-clockwise loops, directed edges used once.
  std::vector<double> localOffset(nf);
  std::vector<double> normalUncertainty(nf);
  const double roundoff = 16.0 * std::numeric_limits<double>::epsilon() * radius_;
  std::unordered_map<std::uint64_t, int> edgeFace;  // directed edge -> face
  std::unordered_map<std::uint64_t, int> facePos;   // (face, vertex) -> position in its loop
  for (int f = 0; f < nf; ++f) {
    const IndexRange fv = faceVertices(f);
    const Vector3d& n = faceNormals_[f];
    if (fv.size() < 3) return fail("face ", f, " has ", fv.size(), " vertices");
    if (std::abs(n.norm() - 1.0) > 1e-12) return fail("face ", f, " normal is not unit");
    localOffset[f] = faceOffsets_[f] - n.dot(center_);
    for (int i = 0; i < fv.size(); ++i) {
      const int v = fv[i];
      if (v < 0 || v >= nv) return fail("face ", f, " has vertex index ", v, " out of range");
      if (!facePos.emplace(edgeKey(f, v), i).second) {
        return fail("face ", f, " lists vertex ", v, " twice");
      }
      const double off = n.dot(local_[v]) - localOffset[f];
      if (std::abs(off) > tol) {
        return fail("face ", f, " is not planar: vertex ", v, " is ", off, " off its plane");
      }
      if (!edgeFace.emplace(edgeKey(v, fv[(i + 1) % fv.size()]), f).second) {
        return fail("directed edge (", v, ", ", fv[(i + 1) % fv.size()], ") is used twice");
      }
    }
    const Vector3d area = newellVector(fv, [&](int v) { return local_[v]; });
    if (!(area.dot(n) > 0.0)) return fail("face ", f, " is not counter-clockwise about its normal");
    for (int i = 0; i < fv.size(); ++i) {  // a convex polygon: every corner turns left
      const Vector3d& a = local_[fv[i]];
      const Vector3d& b = local_[fv[(i + 1) % fv.size()]];
      const Vector3d& c = local_[fv[(i + 2) % fv.size()]];
      if (!((b - a).cross(c - b).dot(n) > 0.0)) {
        return fail("face ", f, " is not convex at vertex ", fv[(i + 1) % fv.size()]);
      }
    }
    // How far the normal can turn with its vertices moving by no more than their band, the
    // flatness tolerance and round-off: (band + flatTolerance + round-off) / width, width the
    // face's extent across its longest chord; plus kCoplanarAngle, by which the facets merged
    // into one face may disagree. Rings may turn the wrong way by that much at nearly flat
    // vertices (where merging and vertex removal within the tolerance decide the last digits).
    const PlaneFit fit = fitPlane(
        fv, [&](int v) { return local_[v]; }, n);
    normalUncertainty[f] = fit.width > 0.0
                               ? (fit.band + flatTol_ + roundoff) / fit.width + tol::kCoplanarAngle
                               : std::numeric_limits<double>::infinity();
  }
  for (const auto& [key, face] : edgeFace) {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    if (edgeFace.count(edgeKey(b, a)) == 0) {
      return fail("edge (", a, ", ", b, ") of face ", face, " has no twin");
    }
  }
  const int ne = static_cast<int>(edgeFace.size() / 2);
  if (ne != numEdges()) return fail("numEdges() = ", numEdges(), " but faces have ", ne, " edges");
  if (nv - ne + nf != 2) return fail("Euler characteristic V - E + F = ", nv - ne + nf);

  // Convexity: every vertex inside every face plane (solids; O(V F), only when asked), or
  // inside every edge of the polygon.
  if (solid) {
    for (int f = 0; f < nf && globalConvexity; ++f) {
      for (int v = 0; v < nv; ++v) {
        const double off = faceNormals_[f].dot(local_[v]) - localOffset[f];
        if (off > tol) return fail("vertex ", v, " is ", off, " outside face ", f);
      }
    }
  } else {
    // Face 0 lists the vertices in order, so the face loop above has checked every left turn.
    const Vector3d& n = faceNormals_[0];
    for (int i = 0; i < nv; ++i) {
      const Vector3d& a = local_[i];
      const Vector3d& b = local_[(i + 1) % nv];
      const Vector3d out = (b - a).cross(n).normalized();
      for (int v = 0; v < nv; ++v) {
        if (out.dot(local_[v] - a) > tol) {
          return fail("vertex ", v, " is outside edge (", i, ", ", (i + 1) % nv, ")");
        }
      }
    }
  }

  // Rings: ring face j holds the edges (v, nbr_j) and (v, nbr_{j+1}), with v's successor nbr_j
  // and predecessor nbr_{j+1} in that face's counter-clockwise loop.
  auto posIn = [&](int f, int v) {
    const auto it = facePos.find(edgeKey(f, v));
    return it == facePos.end() ? -1 : it->second;
  };
  for (int v = 0; v < nv; ++v) {
    const IndexRange nb = neighbors(v);
    const IndexRange ring = vertexFaces(v);
    const int k = nb.size();
    if (ring.size() != k)
      return fail("vertex ", v, " has ", k, " neighbours but ", ring.size(), " ring faces");
    if (k < (solid ? 3 : 2)) return fail("vertex ", v, " has only ", k, " neighbours");
    for (int j = 0; j < k; ++j) {
      const int u = nb[j];
      if (u < 0 || u >= nv || u == v) return fail("vertex ", v, " has a bad neighbour ", u);
      const IndexRange back = neighbors(u);
      if (std::find(back.begin(), back.end(), v) == back.end()) {
        return fail("neighbours are not symmetric: ", u, " of ", v);
      }
      const int f = ring[j];
      if (f < 0 || f >= nf) return fail("vertex ", v, " has a bad ring face ", f);
      const int i = posIn(f, v);
      if (i < 0) return fail("ring face ", f, " of vertex ", v, " does not contain it");
      const IndexRange fv = faceVertices(f);
      const int m = fv.size();
      if (fv[(i + 1) % m] != nb[j] || fv[(i + m - 1) % m] != nb[(j + 1) % k]) {
        return fail("ring of vertex ", v, ": face ", f, " is not between neighbours ", nb[j],
                    " and ", nb[(j + 1) % k]);
      }
      if (solid) {
        for (int t = 0; t < j; ++t) {
          if (ring[t] == f) return fail("vertex ", v, " has face ", f, " twice in its ring");
          if (nb[t] == u) return fail("vertex ", v, " has neighbour ", u, " twice");
        }
        // The Gauss image of edge (v, nbr_j) runs from ring normal j-1 to ring normal j, counter-
        // clockwise seen from outside, so n_{j-1} x n_j points along v - nbr_j. Allowed the
        // other way by no more than the two normals' uncertainty.
        const int prev = ring[(j + k - 1) % k];
        const Vector3d turn = faceNormals_[prev].cross(faceNormals_[f]);
        const Vector3d edge = (local_[u] - local_[v]).normalized();
        if (!(turn.dot(edge) < normalUncertainty[prev] + normalUncertainty[f])) {
          return fail("ring normals of vertex ", v, " are not counter-clockwise at edge to ", u,
                      " (by ", turn.dot(edge), " rad)");
        }
      }
    }
  }
  return "";
}

}  // namespace deepcheck::deep
