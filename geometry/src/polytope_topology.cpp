// The invariants of a ConvexPolytope (ConvexPolytope::validate): counts, face loops, convexity,
// vertex rings and the Gauss-map order of their normals.

#include "polytope_internal.h"

#include "deepcheck/geometry/tolerances.h"

#include <sstream>
#include <unordered_map>

namespace deepcheck::geometry {

using namespace detail;

namespace {

/// The parts, streamed into one message.
template <class... Parts>
std::string message(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  return out.str();
}

}  // namespace

/// The checks of checkInvariants, in order; each returns a description of the first violation
/// found, or an empty string. A friend of ConvexPolytope.
class PolytopeInvariants {
 public:
  explicit PolytopeInvariants(const ConvexPolytope& p)
      : p_(p),
        nv_(p.numVertices()),
        nf_(p.numFaces()),
        tol_(p.hullTolerance()),
        solid_(p.kind_ == PolytopeKind::Polyhedron) {}

  std::string check(bool globalConvexity) {
    std::string error = counts();
    if (error.empty()) error = kind();
    if (!error.empty() || p_.kind_ == PolytopeKind::Point || p_.kind_ == PolytopeKind::Segment) {
      return error;
    }
    for (int f = 0; f < nf_ && error.empty(); ++f) error = face(f);
    if (error.empty()) error = closedSurface();
    if (error.empty()) error = solid_ ? (globalConvexity ? solidConvexity() : "") : polygonConvexity();
    for (int v = 0; v < nv_ && error.empty(); ++v) error = ring(v);
    return error;
  }

 private:
  std::string counts() const;
  std::string kind() const;
  std::string face(int f);
  std::string closedSurface() const;
  std::string solidConvexity() const;
  std::string polygonConvexity() const;
  std::string ring(int v) const;
  std::string ringEdge(int v, int j) const;
  /// Position of vertex v in face f's loop, or -1.
  int posIn(int f, int v) const {
    const auto it = facePos_.find(edgeKey(f, v));
    return it == facePos_.end() ? -1 : it->second;
  }

  const ConvexPolytope& p_;
  const int nv_;
  const int nf_;
  const double tol_;
  const bool solid_;
  std::vector<double> localOffset_ = std::vector<double>(nf_);
  std::vector<double> normalUncertainty_ = std::vector<double>(nf_);
  std::unordered_map<std::uint64_t, int> edgeFace_;  // directed edge -> face
  std::unordered_map<std::uint64_t, int> facePos_;   // (face, vertex) -> position in its loop
};

std::string PolytopeInvariants::counts() const {
  if (nv_ < 1) return message("no vertices");
  if (static_cast<int>(p_.local_.size()) != nv_ || static_cast<int>(p_.adjStart_.size()) != nv_ + 1 ||
      static_cast<int>(p_.faceStart_.size()) != nf_ + 1 || static_cast<int>(p_.faceOffsets_.size()) != nf_) {
    return message("array sizes do not match the counts");
  }
  if (p_.adjStart_[nv_] != static_cast<int>(p_.adjVerts_.size())) return message("adjacency size");
  if (!p_.adjFaces_.empty() && p_.adjFaces_.size() != p_.adjVerts_.size()) return message("ring size");
  for (int v = 0; v < nv_; ++v) {
    if (!p_.vertices_[v].allFinite()) return message("vertex ", v, " is not finite");
  }
  if (!(p_.lengthScale_ > 0.0)) return message("lengthScale is not positive");
  return "";
}

std::string PolytopeInvariants::kind() const {
  switch (p_.kind_) {
    case PolytopeKind::Point:
      if (nv_ != 1 || nf_ != 0 || !p_.adjVerts_.empty()) return message("a Point has 1 vertex, no faces");
      return "";
    case PolytopeKind::Segment:
      if (nv_ != 2 || nf_ != 0) return message("a Segment has 2 vertices, no faces");
      if (p_.vertices_[0] == p_.vertices_[1]) return message("Segment vertices coincide");
      if (p_.neighbors(0).size() != 1 || p_.neighbors(0)[0] != 1 || p_.neighbors(1).size() != 1 ||
          p_.neighbors(1)[0] != 0) {
        return message("Segment vertices must be each other's only neighbour");
      }
      return "";
    case PolytopeKind::Polygon:
      if (nv_ < 3 || nf_ != 2) return message("a Polygon has >= 3 vertices and 2 faces");
      if ((p_.faceNormals_[0] + p_.faceNormals_[1]).norm() > tol::kUnitRoundoff) {
        return message("Polygon face normals are not opposite");
      }
      for (int i = 0; i < nv_; ++i) {
        if (p_.faceVertices(0)[i] != i || p_.faceVertices(1)[i] != nv_ - 1 - i) {
          return message("Polygon faces must list 0..k-1 and k-1..0");
        }
      }
      return "";
    case PolytopeKind::Polyhedron:
      if (nv_ < 4 || nf_ < 4) return message("a Polyhedron has >= 4 vertices and faces");
      return "";
  }
  return "";
}

// Face f: size, unit normal, planarity, a counter-clockwise convex loop, directed edges used once;
// records its plane offset and how far its normal is determined (normalUncertainty_).
std::string PolytopeInvariants::face(int f) {
  const IndexRange fv = p_.faceVertices(f);
  const Vector3d& n = p_.faceNormals_[f];
  const auto& local = p_.local_;
  if (fv.size() < 3) return message("face ", f, " has ", fv.size(), " vertices");
  if (std::abs(n.norm() - 1.0) > tol::kUnitRoundoff) return message("face ", f, " normal is not unit");
  localOffset_[f] = p_.faceOffsets_[f] - n.dot(p_.center_);
  for (int i = 0; i < fv.size(); ++i) {
    const int v = fv[i];
    if (v < 0 || v >= nv_) return message("face ", f, " has vertex index ", v, " out of range");
    if (!facePos_.emplace(edgeKey(f, v), i).second) return message("face ", f, " lists vertex ", v, " twice");
    const double off = n.dot(local[v]) - localOffset_[f];
    if (std::abs(off) > tol_) {
      return message("face ", f, " is not planar: vertex ", v, " is ", off, " off its plane");
    }
    if (!edgeFace_.emplace(edgeKey(v, fv[(i + 1) % fv.size()]), f).second) {
      return message("directed edge (", v, ", ", fv[(i + 1) % fv.size()], ") is used twice");
    }
  }
  const Vector3d area = newellVector(fv, [&](int v) { return local[v]; });
  if (!(area.dot(n) > 0.0)) return message("face ", f, " is not counter-clockwise about its normal");
  for (int i = 0; i < fv.size(); ++i) {  // a convex polygon: every corner turns left
    const Vector3d& a = local[fv[i]];
    const Vector3d& b = local[fv[(i + 1) % fv.size()]];
    const Vector3d& c = local[fv[(i + 2) % fv.size()]];
    if (!((b - a).cross(c - b).dot(n) > 0.0)) {
      return message("face ", f, " is not convex at vertex ", fv[(i + 1) % fv.size()]);
    }
  }
  // How far the normal can turn with its vertices moving by no more than their band, the
  // flatness tolerance and round-off: (band + flatTolerance + round-off) / width, width the
  // face's extent across its longest chord; plus kCoplanarAngle, by which the facets merged
  // into one face may disagree. Rings may turn the wrong way by that much at nearly flat
  // vertices (where merging and vertex removal within the tolerance decide the last digits).
  const double roundoff = 16.0 * std::numeric_limits<double>::epsilon() * p_.radius_;
  const PlaneFit fit = fitPlane(
      fv, [&](int v) { return local[v]; }, n);
  normalUncertainty_[f] = fit.width > 0.0 ? (fit.band + p_.flatTol_ + roundoff) / fit.width + tol::kCoplanarAngle
                                          : std::numeric_limits<double>::infinity();
  return "";
}

// Every directed edge has its twin, the edge count matches, and V - E + F = 2.
std::string PolytopeInvariants::closedSurface() const {
  for (const auto& [key, face] : edgeFace_) {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    if (edgeFace_.count(edgeKey(b, a)) == 0) {
      return message("edge (", a, ", ", b, ") of face ", face, " has no twin");
    }
  }
  const int ne = static_cast<int>(edgeFace_.size() / 2);
  if (ne != p_.numEdges()) return message("numEdges() = ", p_.numEdges(), " but faces have ", ne, " edges");
  if (nv_ - ne + nf_ != 2) return message("Euler characteristic V - E + F = ", nv_ - ne + nf_);
  return "";
}

// Every vertex inside every face plane (O(V F), only when asked).
std::string PolytopeInvariants::solidConvexity() const {
  for (int f = 0; f < nf_; ++f) {
    for (int v = 0; v < nv_; ++v) {
      const double off = p_.faceNormals_[f].dot(p_.local_[v]) - localOffset_[f];
      if (off > tol_) return message("vertex ", v, " is ", off, " outside face ", f);
    }
  }
  return "";
}

// Every vertex inside every edge of the polygon. Face 0 lists the vertices in order, so the face
// check has seen every left turn.
std::string PolytopeInvariants::polygonConvexity() const {
  const Vector3d& n = p_.faceNormals_[0];
  const auto& local = p_.local_;
  for (int i = 0; i < nv_; ++i) {
    const Vector3d& a = local[i];
    const Vector3d& b = local[(i + 1) % nv_];
    const Vector3d out = (b - a).cross(n).normalized();
    for (int v = 0; v < nv_; ++v) {
      if (out.dot(local[v] - a) > tol_) {
        return message("vertex ", v, " is outside edge (", i, ", ", (i + 1) % nv_, ")");
      }
    }
  }
  return "";
}

// Rings: ring face j holds the edges (v, nbr_j) and (v, nbr_{j+1}), with v's successor nbr_j and
// predecessor nbr_{j+1} in that face's counter-clockwise loop.
std::string PolytopeInvariants::ring(int v) const {
  const IndexRange nb = p_.neighbors(v);
  const IndexRange ring = p_.vertexFaces(v);
  const int k = nb.size();
  if (ring.size() != k) return message("vertex ", v, " has ", k, " neighbours but ", ring.size(), " ring faces");
  if (k < (solid_ ? 3 : 2)) return message("vertex ", v, " has only ", k, " neighbours");
  for (int j = 0; j < k; ++j) {
    std::string error = ringEdge(v, j);
    if (!error.empty()) return error;
  }
  return "";
}

// Neighbour j of vertex v and ring face j: symmetric, in order, and (solids) each once, with the
// ring normals turning counter-clockwise across the edge.
std::string PolytopeInvariants::ringEdge(int v, int j) const {
  const IndexRange nb = p_.neighbors(v);
  const IndexRange ring = p_.vertexFaces(v);
  const int k = nb.size();
  const int u = nb[j];
  if (u < 0 || u >= nv_ || u == v) return message("vertex ", v, " has a bad neighbour ", u);
  const IndexRange back = p_.neighbors(u);
  if (std::find(back.begin(), back.end(), v) == back.end()) {
    return message("neighbours are not symmetric: ", u, " of ", v);
  }
  const int f = ring[j];
  if (f < 0 || f >= nf_) return message("vertex ", v, " has a bad ring face ", f);
  const int i = posIn(f, v);
  if (i < 0) return message("ring face ", f, " of vertex ", v, " does not contain it");
  const IndexRange fv = p_.faceVertices(f);
  const int m = fv.size();
  if (fv[(i + 1) % m] != nb[j] || fv[(i + m - 1) % m] != nb[(j + 1) % k]) {
    return message("ring of vertex ", v, ": face ", f, " is not between neighbours ", nb[j], " and ", nb[(j + 1) % k]);
  }
  if (!solid_) return "";
  for (int t = 0; t < j; ++t) {
    if (ring[t] == f) return message("vertex ", v, " has face ", f, " twice in its ring");
    if (nb[t] == u) return message("vertex ", v, " has neighbour ", u, " twice");
  }
  // The Gauss image of edge (v, nbr_j) runs from ring normal j-1 to ring normal j, counter-
  // clockwise seen from outside, so n_{j-1} x n_j points along v - nbr_j. Allowed the other way
  // by no more than the two normals' uncertainty.
  const int prev = ring[(j + k - 1) % k];
  const Vector3d turn = p_.faceNormals_[prev].cross(p_.faceNormals_[f]);
  const Vector3d edge = (p_.local_[u] - p_.local_[v]).normalized();
  if (!(turn.dot(edge) < normalUncertainty_[prev] + normalUncertainty_[f])) {
    return message("ring normals of vertex ", v, " are not counter-clockwise at edge to ", u, " (by ", turn.dot(edge),
                   " rad)");
  }
  return "";
}

std::string ConvexPolytope::validate() const { return checkInvariants(true); }

std::string ConvexPolytope::checkInvariants(bool globalConvexity) const {
  return PolytopeInvariants(*this).check(globalConvexity);
}

}  // namespace deepcheck::geometry
