// The support mapping of a ConvexPolytope: brute force on small hulls, hill climbing over the
// vertex graph on larger ones, started from a cube-map direction index.

#include "deepcheck/geometry/polytope.h"

#include "probe_icosahedron.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace deepcheck::geometry {

using Eigen::Vector3d;

namespace {

/// support() scans all vertices up to this count; hill climbing only pays off beyond.
constexpr int kBruteForceMaxVertices = 16;
/// prefetchSupportData() requests hulls whose support arrays take at most this many bytes whole
/// (about 250 vertices). A cold expansion's climbs reach most of such a hull; on larger ones they
/// reach only a part, so requesting every line would cost more memory traffic than it saves.
constexpr std::size_t kPrefetchMaxBytes = 16 * 1024;
/// Bytes of a cache line, the step between requests.
constexpr std::size_t kCacheLineBytes = 64;
/// support() searches plateaus of vertices within hullTolerance * |dir| of the best value (the
/// hull is convex within hullTolerance), up to kMaxPlateau vertices.
constexpr int kMaxPlateau = 64;

}  // namespace

int ConvexPolytope::supportBruteForce(const Vector3d& dir) const {
  int best = 0;
  double bestValue = dir.dot(local_[0]);
  const int n = numVertices();
  for (int v = 1; v < n; ++v) {
    const double s = dir.dot(local_[v]);
    if (s > bestValue) {
      bestValue = s;
      best = v;
    }
  }
  return best;
}

namespace {

/// Cell of the cube map (6 faces of `grid` x `grid` cells) that direction d points into, or -1
/// for a zero or non-finite d. Face 2k + (d_k < 0) is the one of the largest |d_k|; the cell
/// coordinates are the other two components divided by |d_k|, each in [-1, 1].
inline int cubeCell(const Vector3d& d, int grid) {
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  int face;
  double m, u, w;
  if (ax >= ay && ax >= az) {
    m = ax;
    face = d.x() < 0.0 ? 1 : 0;
    u = d.y();
    w = d.z();
  } else if (ay >= az) {
    m = ay;
    face = d.y() < 0.0 ? 3 : 2;
    u = d.x();
    w = d.z();
  } else {
    m = az;
    face = d.z() < 0.0 ? 5 : 4;
    u = d.x();
    w = d.y();
  }
  if (!(m > 0.0 && m <= std::numeric_limits<double>::max())) return -1;
  const double half = 0.5 * grid;
  const double s = half / m;
  // Clamped before the cast (a NaN component gives cell 0): a double out of int's range has no
  // defined conversion.
  auto cell = [&](double x) { return x >= 0.0 ? static_cast<int>(std::min(x, grid - 1.0)) : 0; };
  return (face * grid + cell(u * s + half)) * grid + cell(w * s + half);
}

}  // namespace

void ConvexPolytope::buildDirectionIndex() {
  directionIndex_.clear();
  if (numVertices() <= kBruteForceMaxVertices) return;
  constexpr int g = kDirectionGrid;
  std::vector<int> index(6 * g * g, 0);
  int previous = 0;
  for (int face = 0; face < 6; ++face) {
    for (int iu = 0; iu < g; ++iu) {
      for (int iw = 0; iw < g; ++iw) {
        // The cell's centre direction; consecutive cells are neighbours, so each climb is short.
        const double u = -1.0 + (2.0 * iu + 1.0) / g;
        const double w = -1.0 + (2.0 * iw + 1.0) / g;
        const double sign = face % 2 == 0 ? 1.0 : -1.0;
        Vector3d d;
        if (face / 2 == 0) d = Vector3d(sign, u, w);
        else if (face / 2 == 1) d = Vector3d(u, sign, w);
        else d = Vector3d(u, w, sign);
        previous = support(d, previous);  // the index is still empty: a plain climb
        index[(face * g + iu) * g + iw] = previous;
      }
    }
  }
  directionIndex_ = std::move(index);
}

void ConvexPolytope::buildProbeSupports() {
  const probe::Icosahedron& ico = probe::icosahedron();
  int previous = 0;
  for (int i = 0; i < kProbeDirections; ++i) probeSupport_[i] = previous = support(ico.direction[i], previous);
}

void ConvexPolytope::buildFaceSupports() {
  faceSupport_.resize(faceNormals_.size());
  for (int f = 0; f < numFaces(); ++f) faceSupport_[f] = support(faceNormals_[f], faceVertices(f)[0]);
}

namespace {

template <class T>
std::size_t bytesOf(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

template <class T>
void prefetchArray(const std::vector<T>& v) {
  const char* p = reinterpret_cast<const char*>(v.data());
  for (std::size_t offset = 0; offset < bytesOf(v); offset += kCacheLineBytes) __builtin_prefetch(p + offset);
}

}  // namespace

void ConvexPolytope::prefetchSupportData() const {
  if (bytesOf(local_) + bytesOf(adjStart_) + bytesOf(adjVerts_) + bytesOf(directionIndex_) > kPrefetchMaxBytes) return;
  prefetchArray(local_);
  prefetchArray(adjStart_);
  prefetchArray(adjVerts_);
  prefetchArray(directionIndex_);
}

int ConvexPolytope::supportStart(const Vector3d& dir) const {
  if (directionIndex_.empty()) return -1;
  const int cell = cubeCell(dir, kDirectionGrid);
  return cell < 0 ? -1 : directionIndex_[cell];
}

int ConvexPolytope::support(const Vector3d& dir, int hint) const {
  const int n = numVertices();
  if (n <= kBruteForceMaxVertices) return supportBruteForce(dir);
  // Steepest ascent over the vertex graph. On a convex polytope a vertex no neighbour of which
  // is higher is a global maximum. Hulls are convex within a tolerance only, and at a very short
  // edge that is enough to stop the climb far from the maximum (the edge's direction is set by
  // the tolerance, not by the shape). So when neighbours are lower by less than the slack, the
  // plateau they form is searched for a higher vertex before stopping. Every move raises the
  // value strictly, so ties cannot cycle. The slack (a square root) is computed only where the
  // climb stops: its test needs just the highest neighbour, and only when none is higher.
  int v = (hint >= 0 && hint < n) ? hint : 0;
  double value = dir.dot(local_[v]);
  // Start from the direction index's vertex when it is higher than the hint: it lies near the
  // support, while a hint (the last support of a pair) may be far when the direction swung.
  if (const int start = supportStart(dir); start >= 0) {
    const double startValue = dir.dot(local_[start]);
    if (startValue > value) {
      v = start;
      value = startValue;
    }
  }
  for (;;) {
    int best = v;
    double bestValue = value;
    double highestLower = -std::numeric_limits<double>::infinity();  // neighbours not higher
    for (int k = adjStart_[v]; k < adjStart_[v + 1]; ++k) {
      const double s = dir.dot(local_[adjVerts_[k]]);
      if (s > bestValue) {
        bestValue = s;
        best = adjVerts_[k];
      } else {
        highestLower = std::max(highestLower, s);
      }
    }
    if (best == v) {
      // No neighbour is higher (bestValue == value throughout, so every one went to the else).
      const double slack = hullTolerance() * dir.norm();
      if (!(highestLower >= value - slack)) return v;
      std::array<int, kMaxPlateau> plateau;
      int count = 0;
      plateau[count++] = v;
      for (int i = 0; i < count && best == v; ++i) {
        for (int k = adjStart_[plateau[i]]; k < adjStart_[plateau[i] + 1]; ++k) {
          const int u = adjVerts_[k];
          const double s = dir.dot(local_[u]);
          if (s > bestValue) {
            bestValue = s;
            best = u;
          } else if (s >= value - slack && count < kMaxPlateau &&
                     std::find(plateau.begin(), plateau.begin() + count, u) == plateau.begin() + count) {
            plateau[count++] = u;
          }
        }
      }
      if (best == v) return v;
    }
    v = best;
    value = bestValue;
  }
}

}  // namespace deepcheck::geometry
