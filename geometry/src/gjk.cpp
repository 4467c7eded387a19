// GJK distance and overlap between two convex polytopes (see gjk.h for the contract).
//
// The loop (Gilbert, Johnson, Keerthi 1988, in van den Bergen's formulation):
//   w0 = support of M in -d0 (d0: the warm-start or initial direction); W = {w0}; v = w0
//   repeat
//     w = support of M in -v                       (the point of M with the smallest v.w)
//     stop when |v|^2 - v.w <= kGjkRelative |v|^2  (upper bound |v| and lower bound v.w/|v|
//                                                   on the distance agree)
//     W = smallest sub-simplex of W + {w} whose hull holds the point closest to the origin
//     v = that closest point
// M = B - A is never built: a support point is a pair of vertex indices (a, b), so the final
// simplex gives the witness points as exact convex combinations of hull vertices.
//
// Sub-simplex step: signed volumes (Montanari, Petrinic, Barbieri 2017). The barycentric weights
// of the origin's projection on a segment, triangle or tetrahedron are ratios of signed lengths,
// areas or volumes; a sub-simplex is searched only where a weight is not positive. Differences
// from the paper:
//  - Segment weights are computed each from the other end (no 1 - x). Triangle weights are
//    signed areas in the triangle's own plane, in a frame built on its longest edge, with the
//    apex weight first and the others derived from it so the reconstructed point stays accurate
//    on slivers (see onTriangle); the paper projects on a coordinate plane instead.
//  - A tetrahedron flatter than kParallelSine (relative to its longest edge) never claims to
//    enclose the origin, and all its faces are searched: its volume signs are noise. Whatever is
//    searched, every candidate is a convex combination of support points, so keeping the closest
//    can never undershoot the distance.
//  - Besides the gap test, the loop stops when a support point repeats (same index pair) or when
//    v did not get shorter (round-off has taken over); the previous simplex is then kept. Before
//    giving up on such a stall with the gap still open, the runner-up vertices (best neighbours
//    of the support vertices) are tried: near contact between nearly parallel edges the support
//    choice is decided by v's round-off, and the right vertex is the neighbour.
//  - The search direction and the final normal are the simplex triangle's normal (scaled by |v|)
//    when that is more precise than v / |v| (see accurateDirection): near contact between nearly
//    parallel faces, v's round-off would otherwise decide which vertex is the support.
//
// Contact classification. When v falls within kContactRelative * L of the origin, GJK alone
// cannot tell a touching pair from a deep overlap whose origin happens to lie on a simplex face
// (two identical boxes at the same pose do that: the supports are symmetric). The same happens
// when an enclosing tetrahedron has the origin within that tolerance of a face. In those cases
// four more (boolean) GJK runs test whether the points delta * g_k are inside M, where g_k are the
// corners of a regular tetrahedron in a fixed generic orientation and delta = kFlatRelative * L.
// If all four are enclosed, a ball of radius delta / 3 around the origin lies in M: Overlapping.
// Otherwise the penetration, if any, is thinner than delta (flat contact): Touching.

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/tolerances.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::geometry {

const char* toString(GjkStatus s) {
  switch (s) {
    case GjkStatus::Separated:
      return "Separated";
    case GjkStatus::Overlapping:
      return "Overlapping";
    case GjkStatus::Touching:
      return "Touching";
    case GjkStatus::MaxIterations:
      return "MaxIterations";
  }
  return "unknown";
}

namespace {

using Eigen::Vector3d;

/// Iteration cap of one GJK run. GJK on polytopes converges in a handful of iterations (rarely
/// more than 20 on 200-vertex hulls); the cap only guards against round-off cycling.
constexpr int kMaxIterations = 128;

/// A point of M = B - A (minus the probe shift) and the vertex pair it comes from.
struct SupportPoint {
  Vector3d w = Vector3d::Zero();
  int a = 0;
  int b = 0;
};

/// Support mapping of M - shift, in frame P, with hill-climbing hints carried from call to call.
class MinkowskiSupport {
 public:
  MinkowskiSupport(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const Vector3d& shift,
                   int hintA, int hintB)
      : A_(A), B_(B), frame_(frame), shift_(shift), hintA_(hintA), hintB_(hintB) {}

  /// The point of M - shift maximizing d.x.
  SupportPoint operator()(const Vector3d& d) {
    hintA_ = A_.support(-d, hintA_);
    hintB_ = B_.support(frame_.toB(d), hintB_);
    return point(hintA_, hintB_);
  }

  /// The points (a', p.b) and (p.a, b') of M - shift, where a' is the neighbour of p.a that is
  /// best in A along -d (A's part of the support in d), b' the neighbour of p.b best in B along d.
  /// An index equals p's when it has no neighbour.
  std::array<SupportPoint, 2> runnersUp(const Vector3d& d, const SupportPoint& p) const {
    int a2 = p.a;
    double bestA = -std::numeric_limits<double>::infinity();
    for (int x : A_.neighbors(p.a)) {
      const double h = -d.dot(A_.vertex(x));
      if (h > bestA) {
        bestA = h;
        a2 = x;
      }
    }
    const Vector3d dB = frame_.toB(d);
    int b2 = p.b;
    double bestB = -std::numeric_limits<double>::infinity();
    for (int y : B_.neighbors(p.b)) {
      const double h = dB.dot(B_.vertex(y));
      if (h > bestB) {
        bestB = h;
        b2 = y;
      }
    }
    return {point(a2, p.b), point(p.a, b2)};
  }

  SupportPoint point(int a, int b) const {
    SupportPoint p;
    p.a = a;
    p.b = b;
    p.w = frame_.vertexB(B_, b) - PairFrame::vertexA(A_, a) - shift_;
    return p;
  }

  int hintA() const { return hintA_; }
  int hintB() const { return hintB_; }

 private:
  const ConvexPolytope& A_;
  const ConvexPolytope& B_;
  const PairFrame& frame_;
  Vector3d shift_;
  int hintA_;
  int hintB_;
};

/// The closest point to the origin of (a sub-simplex of) the current simplex.
struct Closest {
  int n = 0;                    ///< points kept
  std::array<int, 4> idx{};     ///< their positions in the simplex being reduced
  std::array<double, 4> lam{};  ///< barycentric weights, > 0, summing to 1
  Vector3d v = Vector3d::Zero();
  double vv = std::numeric_limits<double>::infinity();
};

void keepCloser(Closest& best, const Closest& c) {
  // Strict: on a tie the candidate found first (the smaller sub-simplex) stays.
  if (c.vv < best.vv) best = c;
}

Closest onVertex(const Vector3d* s, int i) {
  Closest c;
  c.n = 1;
  c.idx[0] = i;
  c.lam[0] = 1.0;
  c.v = s[i];
  c.vv = c.v.squaredNorm();
  return c;
}

Closest onSegment(const Vector3d* s, int i, int j) {
  const Vector3d e = s[j] - s[i];
  // Signed lengths of the origin's projection on the line, each measured from the other end
  // (s_j.e = |e|^2 - (-s_i.e)), so neither weight is 1 minus the other.
  const double li = s[j].dot(e);
  const double lj = -s[i].dot(e);
  if (li > 0.0 && lj > 0.0) {
    Closest c;
    c.n = 2;
    c.idx[0] = i;
    c.idx[1] = j;
    const double sum = li + lj;
    c.lam[0] = li / sum;
    c.lam[1] = lj / sum;
    c.v = c.lam[0] * s[i] + c.lam[1] * s[j];
    c.vv = c.v.squaredNorm();
    return c;
  }
  // The projection is beyond an end (or the segment is too short to tell): nearer vertex.
  Closest best = onVertex(s, i);
  keepCloser(best, onVertex(s, j));
  return best;
}

Closest onTriangle(const Vector3d* s, int i, int j, int k) {
  // Signed areas in the triangle's own plane, on a frame built from its longest edge (a, b):
  // u1 along the edge, u2 towards the apex c, at height h. The origin's foot has coordinates
  // (x, y); its weights are lc = y / h (the apex) and lb from the position along the edge once
  // the apex share is known, la = 1 - lb - lc. Computing lb from lc keeps the reconstructed point
  // consistent: an error in lc (large for a sliver, |y| and h are both small) moves the point by
  // only error * h. Independent 3-D triple products per weight would each err by eps * L^2 and
  // move the point by eps * L^2 / h along the edge: on the slivers that nearly parallel edges
  // produce near contact, that is far more than the distance itself.
  const std::array<int, 3> id = {i, j, k};
  int base = 0;  // edge (id[base], id[base + 1]) is the longest
  double longest2 = -1.0;
  for (int e = 0; e < 3; ++e) {
    const double len2 = (s[id[(e + 1) % 3]] - s[id[e]]).squaredNorm();
    if (len2 > longest2) {
      longest2 = len2;
      base = e;
    }
  }
  const int a = id[base], b = id[(base + 1) % 3], c = id[(base + 2) % 3];
  if (!(longest2 > 0.0)) return onVertex(s, a);  // three copies of one point
  const double baseLen = std::sqrt(longest2);
  const Vector3d eb = s[b] - s[a];
  const Vector3d ec = s[c] - s[a];
  const Vector3d u1 = eb / baseLen;
  Vector3d hv = ec - ec.dot(u1) * u1;
  // Second Gram-Schmidt pass: for a sliver, hv is a small difference of long vectors, and its
  // leftover component along u1 (eps * L) would be a large tilt of u2 within the plane.
  hv -= hv.dot(u1) * u1;
  const double h = hv.norm();
  // Collinear: c lies on the longest edge, which is then the whole triangle.
  if (!(h > 0.0)) return onSegment(s, a, b);
  const Vector3d u2 = hv / h;
  const double xc = ec.dot(u1);
  const double hc = ec.dot(u2);
  const double x = -s[a].dot(u1);
  const double y = -s[a].dot(u2);
  const double lc = y / hc;
  const double lb = (x - lc * xc) / baseLen;
  const double la = 1.0 - lb - lc;
  Closest best;
  if (la > 0.0 && lb > 0.0 && lc > 0.0) {
    best.n = 3;
    best.idx = {a, b, c, 0};
    best.lam = {la, lb, lc, 0.0};
    best.v = s[a] + lb * eb + lc * ec;
    best.vv = best.v.squaredNorm();
    // At least as high as it is far from the origin, the triangle's plane is well determined and
    // no edge comes closer than its interior point.
    if (h * h >= best.vv) return best;
  }
  // Otherwise the edges are searched, all three: on a sliver thinner than its distance to the
  // origin the plane (u2) is ill-determined and the weights, signs included, are noise, while the
  // edges are then within h^2 / (2 |v|) of the answer. The strict comparison keeps the interior
  // point on ties.
  keepCloser(best, onSegment(s, a, b));
  keepCloser(best, onSegment(s, b, c));
  keepCloser(best, onSegment(s, c, a));
  return best;
}

constexpr int kTetraFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};  // opposite vertex i

/// The signed volumes of a tetrahedron s[0..3] and of the four with one vertex replaced by the
/// origin.
struct TetrahedronVolumes {
  double det = 0.0;           ///< 6 * signed volume
  std::array<double, 4> c{};  ///< det with vertex i replaced by the origin; they sum to det
  bool flat = true;           ///< coplanar points, or worse: the signs are noise

  /// The origin strictly inside. A flat tetrahedron never claims this: it could only enclose the
  /// origin within round-off of its plane anyway.
  bool enclosesOrigin() const {
    return !flat && c[0] * det > 0.0 && c[1] * det > 0.0 && c[2] * det > 0.0 && c[3] * det > 0.0;
  }
};

TetrahedronVolumes tetrahedronVolumes(const Vector3d* s) {
  const Vector3d e1 = s[1] - s[0];
  const Vector3d e2 = s[2] - s[0];
  const Vector3d e3 = s[3] - s[0];
  TetrahedronVolumes t;
  t.det = e1.dot(e2.cross(e3));
  const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), e3.squaredNorm(), (s[2] - s[1]).squaredNorm(),
                                    (s[3] - s[1]).squaredNorm(), (s[3] - s[2]).squaredNorm()});
  // Flat: |det| = 6 * volume is below kParallelSine * longest^3.
  t.flat = !(std::abs(t.det) > tol::kParallelSine * longest2 * std::sqrt(longest2));
  // c[i] / det is the origin's barycentric weight. Each is computed on differences from a vertex,
  // so that operands have the size of the simplex: e.g. c[3] = det[e1, e2, 0 - s0].
  const Vector3d o0 = -s[0];
  t.c = {s[1].dot((s[2] - s[1]).cross(s[3] - s[1])), o0.dot(e2.cross(e3)), e1.dot(o0.cross(e3)), e1.dot(e2.cross(o0))};
  return t;
}

Closest onTetrahedron(const Vector3d* s) {
  const TetrahedronVolumes t = tetrahedronVolumes(s);
  if (t.enclosesOrigin()) {  // M overlaps the origin
    Closest out;
    out.n = 4;
    out.idx = {0, 1, 2, 3};
    const double sum = t.c[0] + t.c[1] + t.c[2] + t.c[3];
    for (int i = 0; i < 4; ++i) out.lam[i] = t.c[i] / sum;
    out.v = Vector3d::Zero();
    out.vv = 0.0;
    return out;
  }
  // Outside: the closest point is on a face the origin sees (the opposite weight is not
  // positive). When flat, search every face.
  Closest best;
  for (int i = 0; i < 4; ++i) {
    if (t.flat || !(t.c[i] * t.det > 0.0)) {
      keepCloser(best, onTriangle(s, kTetraFace[i][0], kTetraFace[i][1], kTetraFace[i][2]));
    }
  }
  return best;
}

/// Smallest distance from the origin to the face planes of a tetrahedron.
double nearestFacePlane(const std::array<SupportPoint, 4>& p) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& f : kTetraFace) {
    const Vector3d& a = p[f[0]].w;
    const Vector3d n = (p[f[1]].w - a).cross(p[f[2]].w - a);
    const double nn = n.norm();
    if (nn > 0.0) nearest = std::min(nearest, std::abs(a.dot(n)) / nn);
  }
  return nearest;
}

enum class Exit {
  Converged,       ///< the gap closed, a support point repeated, or v stopped shrinking
  Enclosed,        ///< a tetrahedron of support points holds the origin
  NearOrigin,      ///< |v| <= nearTol: the origin is within tolerance of the simplex
  SeparatingAxis,  ///< (early exit only) v.w > sepTol * |v|: a separating plane was found
  MaxIterations,
};

struct Run {
  Exit exit = Exit::MaxIterations;
  int n = 0;
  std::array<SupportPoint, 4> pts{};
  std::array<double, 4> lam{};
  Vector3d v = Vector3d::Zero();
  double vv = 0.0;
  Vector3d lastDir = Vector3d::UnitX();  ///< the v whose -v gave the last support point
  int iterations = 0;
  double lower = 0.0;  ///< the largest lower bound on the distance seen, d.w / |d| over directions d
};

/// Unit vector along v, the current closest point. v carries an absolute error of a few ulps of
/// the pair's coordinates (eps * L), so v / |v| turns by about eps * L / |v|: near contact that
/// is enough to pick the wrong vertex among nearly parallel faces, and it tilts the witness
/// planes over the length of a face. When the simplex is a triangle with v inside it, v is the
/// foot of the origin on its plane, and the plane's normal e1 x e2 turns by only about
/// eps * L * longest / |e1 x e2| = eps * L / h, h the triangle's height over its longest edge.
/// Whichever is smaller wins: the triangle's normal when h > |v|.
Vector3d accurateDirection(const Run& r) {
  const Vector3d vHat = r.v.normalized();
  if (r.n != 3) return vHat;
  const Vector3d e1 = r.pts[1].w - r.pts[0].w;
  const Vector3d e2 = r.pts[2].w - r.pts[0].w;
  const Vector3d n = e1.cross(e2);
  const double longest = std::sqrt(std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()}));
  if (!(n.norm() > longest * std::sqrt(r.vv))) return vHat;
  const Vector3d nHat = n.normalized();
  return nHat.dot(vHat) >= 0.0 ? nHat : Vector3d(-nHat);
}

enum class Step { Progress, Enclosed, NoProgress };

/// Adds p to the simplex of r and reduces it to the sub-simplex closest to the origin, unless that
/// is no closer than the current v (then r is left unchanged).
Step addPoint(Run& r, const SupportPoint& p) {
  for (int i = 0; i < r.n; ++i) {
    if (r.pts[i].a == p.a && r.pts[i].b == p.b) return Step::NoProgress;
  }
  std::array<SupportPoint, 4> cand = r.pts;
  cand[r.n] = p;
  const int m = r.n + 1;
  std::array<Vector3d, 4> s;
  for (int i = 0; i < m; ++i) s[i] = cand[i].w;
  const Closest c = m == 2   ? onSegment(s.data(), 0, 1)
                    : m == 3 ? onTriangle(s.data(), 0, 1, 2)
                             : onTetrahedron(s.data());
  if (c.n == 4) {
    r.n = 4;
    r.pts = cand;
    r.lam = c.lam;
    r.v = Vector3d::Zero();
    r.vv = 0.0;
    return Step::Enclosed;
  }
  // No progress: round-off dominates. Keep the previous simplex, which is at least as good.
  if (!(c.vv < r.vv)) return Step::NoProgress;
  r.n = c.n;
  for (int i = 0; i < c.n; ++i) {
    r.pts[i] = cand[c.idx[i]];
    r.lam[i] = c.lam[i];
  }
  r.v = c.v;
  r.vv = c.vv;
  return Step::Progress;
}

/// Stalls worth a second look per run (see the stall comment in runGjk).
constexpr int kMaxStallRetries = 4;

/// One GJK run on M - shift (the shift is inside `support`). With `earlyExit`, stops at the first
/// direction proving the distance exceeds sepTol. Converged when the bounds agree to kGjkRelative,
/// or to `gap` (relative, of |v|^2) once the lower bound exceeds nearTol.
Run runGjk(MinkowskiSupport& support, const Vector3d& dir0, bool earlyExit, double sepTol, double nearTol,
           double gap = tol::kGjkRelative) {
  Run r;
  r.lastDir = dir0;
  const SupportPoint first = support(-dir0);
  r.n = 1;
  r.pts[0] = first;
  r.lam[0] = 1.0;
  r.v = first.w;
  r.vv = r.v.squaredNorm();
  // dir0 is not a point of M, but dir0.w0 is still the smallest of dir0.x over M.
  const double dir0Norm = dir0.norm();
  if (dir0Norm > 0.0) r.lower = std::max(0.0, dir0.dot(first.w) / dir0Norm);
  if (earlyExit && dir0.dot(first.w) > sepTol * dir0Norm) {
    r.exit = Exit::SeparatingAxis;
    return r;
  }

  int retries = 0;
  for (int iter = 1; iter <= kMaxIterations; ++iter) {
    r.iterations = iter;
    if (r.vv <= nearTol * nearTol) {
      r.exit = Exit::NearOrigin;
      return r;
    }
    // The search direction is v, its direction taken from the simplex's plane when more precise.
    const Vector3d dir = accurateDirection(r) * std::sqrt(r.vv);
    const SupportPoint p = support(-dir);
    r.lastDir = dir;
    const double vw = dir.dot(p.w);
    const double v = std::sqrt(r.vv);
    r.lower = std::max(r.lower, vw / v);
    if (earlyExit && vw > sepTol * v) {
      r.exit = Exit::SeparatingAxis;
      return r;
    }
    if (r.vv - vw <= tol::kGjkRelative * r.vv || (r.vv - vw <= gap * r.vv && r.lower > nearTol)) {
      r.exit = Exit::Converged;
      return r;
    }
    Step step = addPoint(r, p);
    // Stall with the gap still open: the support point repeats or brings no progress although
    // the lower bound v.w / |v| says the distance may be smaller. This happens when |v| is so
    // small that its round-off (eps * L) decides between nearly parallel features (two edges at
    // a small angle, close together): the support is then a coin toss. Give the runner-up
    // vertices a chance: the best neighbour of p.a in A and of p.b in B along the same direction.
    if (step == Step::NoProgress && retries < kMaxStallRetries) {
      ++retries;
      const std::array<SupportPoint, 2> alternatives = support.runnersUp(-dir, p);
      for (const SupportPoint& q : alternatives) {
        if (q.a == p.a && q.b == p.b) continue;
        step = addPoint(r, q);
        if (step != Step::NoProgress) break;
      }
    }
    if (step == Step::Enclosed) {
      r.exit = Exit::Enclosed;
      return r;
    }
    if (step == Step::NoProgress) {
      r.exit = Exit::Converged;
      return r;
    }
  }
  r.exit = Exit::MaxIterations;
  return r;
}

Vector3d initialDirection(const PairFrame& frame, const GjkCache* cache) {
  if (cache != nullptr && cache->direction.allFinite() && cache->direction.squaredNorm() > 0.0) {
    return cache->direction;
  }
  if (frame.t.allFinite() && frame.t.squaredNorm() > 0.0) return frame.t;
  return Vector3d::UnitX();
}

/// Corners of a regular tetrahedron of circumradius 1, in an orientation chosen to be generic
/// (no corner on a coordinate axis, plane or box diagonal), so that the probes do not fall on the
/// symmetric simplices that made the classification necessary.
const std::array<Vector3d, 4>& probeDirections() {
  static const std::array<Vector3d, 4> probes = [] {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Vector3d(0.3, 0.5, 0.8).normalized()).toRotationMatrix();
    const double k = 1.0 / std::sqrt(3.0);
    return std::array<Vector3d, 4>{R * Vector3d(k, k, k), R * Vector3d(k, -k, -k), R * Vector3d(-k, k, -k),
                                   R * Vector3d(-k, -k, k)};
  }();
  return probes;
}

/// Overlapping when the ball of radius kFlatRelative * L / 3 about the origin is certified to lie
/// in M, else Touching (see the header comment of this file).
GjkStatus classifyContact(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, double L,
                          const Vector3d& dir, int hintA, int hintB) {
  const double delta = tol::kFlatRelative * L;
  for (const Vector3d& g : probeDirections()) {
    MinkowskiSupport support(A, B, frame, delta * g, hintA, hintB);
    // Any positive v.w proves the probe outside M; the contact tolerance (a hundredth of delta)
    // marks an inconclusive run, which also counts as "not certified".
    const Run r = runGjk(support, dir, /*earlyExit=*/true, /*sepTol=*/0.0, tol::kContactRelative * L);
    if (r.exit != Exit::Enclosed) return GjkStatus::Touching;
  }
  return GjkStatus::Overlapping;
}

void updateCache(GjkCache* cache, const Run& r, const MinkowskiSupport& support) {
  if (cache == nullptr) return;
  cache->direction = r.lastDir;
  cache->hintA = support.hintA();
  cache->hintB = support.hintB();
  cache->enclosed = r.exit == Exit::Enclosed;
  if (!cache->enclosed) return;
  for (int i = 0; i < 4; ++i) {
    cache->enclosing.a[i] = r.pts[i].a;
    cache->enclosing.b[i] = r.pts[i].b;
  }
}

}  // namespace

GjkResult gjkDistance(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, GjkCache* cache) {
  const double L = pairLengthScale(A, B, frame);
  const double contactTol = tol::kContactRelative * L;
  MinkowskiSupport support(A, B, frame, Vector3d::Zero(), cache ? cache->hintA : 0, cache ? cache->hintB : 0);
  const Run r = runGjk(support, initialDirection(frame, cache), /*earlyExit=*/false, 0.0, contactTol);

  GjkResult res;
  res.iterations = r.iterations;
  res.simplexSize = r.n;
  res.pointA.setZero();
  res.pointB.setZero();
  for (int i = 0; i < r.n; ++i) {
    res.simplexA[i] = r.pts[i].a;
    res.simplexB[i] = r.pts[i].b;
    res.weights[i] = r.lam[i];
    res.pointA += r.lam[i] * PairFrame::vertexA(A, r.pts[i].a);
    res.pointB += r.lam[i] * frame.vertexB(B, r.pts[i].b);
  }

  switch (r.exit) {
    case Exit::Converged:
    case Exit::SeparatingAxis:  // (only with early exit, not used here)
    case Exit::MaxIterations: {
      // Converged implies |v| > contactTol: the loop checks that before every support call.
      res.status = r.exit == Exit::MaxIterations ? GjkStatus::MaxIterations : GjkStatus::Separated;
      res.distance = std::sqrt(r.vv);
      if (res.distance > 0.0) res.normal = accurateDirection(r);
      break;
    }
    case Exit::NearOrigin:
    case Exit::Enclosed: {
      const bool certain = r.exit == Exit::Enclosed && nearestFacePlane(r.pts) > contactTol;
      res.status = certain ? GjkStatus::Overlapping
                           : classifyContact(A, B, frame, L, r.lastDir, support.hintA(), support.hintB());
      res.distance = 0.0;
      if (res.status == GjkStatus::Touching && r.vv > 0.0) res.normal = r.v / std::sqrt(r.vv);
      break;
    }
  }
  updateCache(cache, r, support);
  return res;
}

bool enclosesOrigin(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                    const MinkowskiTetrahedron& t) {
  std::array<Vector3d, 4> s;
  for (int i = 0; i < 4; ++i) s[i] = frame.vertexB(B, t.b[i]) - PairFrame::vertexA(A, t.a[i]);
  return tetrahedronVolumes(s.data()).enclosesOrigin();
}

bool gjkOverlap(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, GjkCache* cache) {
  const double contactTol = tol::kContactRelative * pairLengthScale(A, B, frame);
  MinkowskiSupport support(A, B, frame, Vector3d::Zero(), cache ? cache->hintA : 0, cache ? cache->hintB : 0);
  const Run r = runGjk(support, initialDirection(frame, cache), /*earlyExit=*/true, contactTol, contactTol);
  updateCache(cache, r, support);
  switch (r.exit) {
    case Exit::SeparatingAxis:
    case Exit::Converged:
      // Converged without enclosing: |v| > contactTol is the distance to within kGjkRelative.
      return false;
    case Exit::Enclosed:
    case Exit::NearOrigin:
      return true;
    case Exit::MaxIterations:
      // Undecided: report a collision, the safe answer for a planner.
      return true;
  }
  return true;
}

bool gjkWithin(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, double within,
               GjkCache* cache) {
  const double contactTol = tol::kContactRelative * pairLengthScale(A, B, frame);
  MinkowskiSupport support(A, B, frame, Vector3d::Zero(), cache ? cache->hintA : 0, cache ? cache->hintB : 0);
  // Early exit on a lower bound above `within`; a simplex point within max(within, contactTol)
  // of the origin proves the answer true.
  const double near = std::max(within, contactTol);
  const Run r = runGjk(support, initialDirection(frame, cache), /*earlyExit=*/true, near, near);
  updateCache(cache, r, support);
  switch (r.exit) {
    case Exit::SeparatingAxis:
      return false;
    case Exit::Converged:
      // v.w >= (1 - kGjkRelative) |v|^2 at convergence: that lower bound decides.
      return !((1.0 - tol::kGjkRelative) * std::sqrt(r.vv) > near);
    case Exit::Enclosed:
    case Exit::NearOrigin:
    case Exit::MaxIterations:
      return true;
  }
  return true;
}

GjkBound gjkBound(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, double near, double far,
                  GjkCache* cache) {
  const double contactTol = tol::kContactRelative * pairLengthScale(A, B, frame);
  MinkowskiSupport support(A, B, frame, Vector3d::Zero(), cache ? cache->hintA : 0, cache ? cache->hintB : 0);
  const double nearTol = std::max(near, contactTol);
  const Run r = runGjk(support, initialDirection(frame, cache), /*earlyExit=*/true, std::max(far, nearTol), nearTol,
                       tol::kGjkBoundGap);
  updateCache(cache, r, support);
  GjkBound b;
  if (r.exit == Exit::SeparatingAxis || r.exit == Exit::Converged) {
    b.lower = r.lower;
    b.within = !(r.lower > nearTol);
  }
  return b;
}

}  // namespace deepcheck::geometry
