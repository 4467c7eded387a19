// bodySignedDistance (body_depth.h): pairwise queries, the separated answer, the upper bound by
// a ray march, and the exact search over the relevant pairs' Minkowski differences.

#include "body_depth_internal.h"

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/geometry/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace deepcheck::geometry {

const char* toString(BodyDepthStatus s) {
  switch (s) {
    case BodyDepthStatus::Separated:
      return "separated";
    case BodyDepthStatus::Certified:
      return "certified";
    case BodyDepthStatus::FaceLimit:
      return "face-limit";
    case BodyDepthStatus::PairNotCertified:
      return "pair-not-certified";
    case BodyDepthStatus::BuildLimit:
      return "build-limit";
  }
  return "unknown";
}

namespace {

using body::Difference;
using body::PosedPiece;

void checkBody(const Body& b, const Eigen::Isometry3d& X_W, const char* which) {
  std::ostringstream msg;
  msg << "bodySignedDistance: body " << which;
  if (b.pieces.empty()) throw std::invalid_argument(msg.str() + " has no pieces");
  checkPose(X_W, (msg.str() + " pose").c_str());
  for (std::size_t i = 0; i < b.pieces.size(); ++i) {
    const BodyPiece& p = b.pieces[i];
    std::ostringstream piece;
    piece << msg.str() << " piece " << i;
    if (p.shape.core == nullptr) throw std::invalid_argument(piece.str() + " has no core polytope");
    if (p.shape.radius != 0.0) {
      piece << " has radius " << p.shape.radius << ": body depth supports polytope pieces only (radius 0)";
      throw std::invalid_argument(piece.str());
    }
    checkPose(p.X_BP, (piece.str() + " pose").c_str());
  }
}

/// The pieces of body b posed in P: world orientation, origin at p_WP. The translation is
/// formed as R_W * p_BP + (p_W - p_WP) so that a body far from the world's origin keeps the
/// digits of its offset from A.
std::vector<PosedPiece> posePieces(const Body& b, const Eigen::Isometry3d& X_W, const Eigen::Vector3d& p_WP) {
  std::vector<PosedPiece> out;
  const Eigen::Vector3d offset = X_W.translation() - p_WP;
  for (const BodyPiece& p : b.pieces) {
    Eigen::Isometry3d X_PP = Eigen::Isometry3d::Identity();
    X_PP.linear() = X_W.linear() * p.X_BP.linear();
    X_PP.translation() = X_W.linear() * p.X_BP.translation() + offset;
    out.push_back(body::posePiece(*p.shape.core, X_PP));
  }
  return out;
}

/// Bodies' length scale: the largest distance of a piece vertex from P's origin.
double lengthScale(const std::vector<PosedPiece>& A, const std::vector<PosedPiece>& B) {
  double L = 0.0;
  for (const auto* pieces : {&A, &B}) {
    for (const PosedPiece& p : *pieces) {
      L = std::max(L, (p.X_PP * p.core->center()).norm() + p.core->boundingRadius());
    }
  }
  return std::max(L, std::numeric_limits<double>::min());
}

/// The pairwise answer of pair (i, j) turned into a body result (witnesses to the world).
BodySignedDistanceResult fromPair(const SignedDistanceResult& r, int i, int j, const Eigen::Vector3d& p_WP) {
  BodySignedDistanceResult out;
  out.distance = r.distance;
  out.normal = r.normal;
  out.pointA = r.pointA + p_WP;
  out.pointB = r.pointB + p_WP;
  out.pieceA = i;
  out.pieceB = j;
  out.certified = r.certified;
  return out;
}

/// Witnesses for a separating point x (in P) on the difference of pieces a and b: B_j moved by
/// -x touches A_i, and GJK between them names the touching points.
void setWitnesses(const PosedPiece& a, const PosedPiece& b, const Eigen::Vector3d& x, const Eigen::Vector3d& p_WP,
                  BodySignedDistanceResult& out) {
  Eigen::Isometry3d X_moved = b.X_PP;
  X_moved.translation() -= x;
  const PairFrame frame = PairFrame::makeUnchecked(*a.core, a.X_PP, *b.core, X_moved);
  const GjkResult g = gjkDistance(*a.core, *b.core, frame);
  out.pointA = frame.X_WP * g.pointA + p_WP;
  out.pointB = out.pointA + x;
}

/// One piece pair's data for the overlapping case.
struct PairInfo {
  SignedDistanceResult result;
  /// No point of M_ij is nearer the origin than this (0 for overlapping or unconverged pairs).
  double distanceLower = 0.0;
  int built = 0;  ///< 0 not built, 1 a solid difference (index in diffs), 2 flat
  int index = -1;
};

/// A separating translation from the bodies' bounding boxes (axes of P): the shortest move of B
/// along an axis after which the boxes only touch, as the point x = -t of the complement of the
/// union (B moved by -x overlaps no piece of A). Its length bounds the depth from above.
Eigen::Vector3d boxSeparation(const std::vector<PosedPiece>& A, const std::vector<PosedPiece>& B) {
  const auto box = [](const std::vector<PosedPiece>& pieces) {
    Eigen::AlignedBox3d b;
    for (const PosedPiece& p : pieces) {
      for (const Eigen::Vector3d& v : p.vertices) b.extend(v);
    }
    return b;
  };
  const Eigen::AlignedBox3d a = box(A);
  const Eigen::AlignedBox3d b = box(B);
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double bestLength = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    // B up to A's top (t > 0) or down to A's bottom (t < 0); x = -t.
    for (const double t : {a.max()[axis] - b.min()[axis], a.min()[axis] - b.max()[axis]}) {
      if (std::abs(t) < bestLength) {
        bestLength = std::abs(t);
        best = Eigen::Vector3d::Zero();
        best[axis] = -t;
      }
    }
  }
  return best;
}

/// What the search needs of a query: the pieces, the bound beyond which facets are left out of
/// the differences (buildDifference's `keep`), and what is left of the build budget.
struct Pieces {
  const std::vector<PosedPiece>& A;
  const std::vector<PosedPiece>& B;
  int nB = 0;
  double keep = std::numeric_limits<double>::infinity();
  double budget = std::numeric_limits<double>::infinity();  ///< BodyDepthOptions::maxBuildCost left
  bool exhausted = false;  ///< a difference was needed that the budget could not pay for
};

/// Builds pair k's difference on first need; returns its index in diffs, or -1 when flat or when
/// the budget cannot pay for it (then P.exhausted is set and nothing is built).
int ensureDifference(std::vector<PairInfo>& pairs, int k, Pieces& P, std::vector<Difference>& diffs) {
  const int nB = P.nB;
  const std::vector<PosedPiece>& A = P.A;
  const std::vector<PosedPiece>& B = P.B;
  PairInfo& p = pairs[static_cast<std::size_t>(k)];
  if (p.built == 0) {
    const double cost = body::differenceCost(A[static_cast<std::size_t>(k / nB)], B[static_cast<std::size_t>(k % nB)]);
    if (cost > P.budget) {
      P.exhausted = true;
      return -1;
    }
    P.budget -= cost;
    Difference d;
    d.pieceA = k / nB;
    d.pieceB = k % nB;
    if (body::buildDifference(A[static_cast<std::size_t>(d.pieceA)], B[static_cast<std::size_t>(d.pieceB)], d,
                              P.keep)) {
      p.built = 1;
      p.index = static_cast<int>(diffs.size());
      diffs.push_back(std::move(d));
    } else {
      p.built = 2;
    }
  }
  return p.built == 1 ? p.index : -1;
}

/// Marches from the origin along u, starting at distance t, across every difference whose
/// interior holds the current point, to the first point held by none: a point of the complement.
/// Gives up (returns infinity) once beyond `cap`.
double marchOut(std::vector<PairInfo>& pairs, Pieces& P, std::vector<Difference>& diffs, const Eigen::Vector3d& u,
                double t, double cap, double tol) {
  bool moved = true;
  while (moved) {
    moved = false;
    for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
      if (t >= cap) return std::numeric_limits<double>::infinity();
      if (pairs[static_cast<std::size_t>(k)].distanceLower >= t) continue;
      const int idx = ensureDifference(pairs, k, P, diffs);
      if (P.exhausted) return std::numeric_limits<double>::infinity();
      if (idx < 0 || body::planeExcess(diffs[static_cast<std::size_t>(idx)], t * u) >= -tol) continue;
      t = body::rayExit(diffs[static_cast<std::size_t>(idx)], u);
      moved = true;
    }
  }
  return t;
}

/// The shortest march out (marchOut) along the separating directions of the overlapping pairs, or
/// `bound` (a point of the complement) when none ends nearer: a point of the complement, the
/// search's start. Each pair's own push-out direction is tried because the body's answer is often
/// one of them (a pair whose push is not blocked by others). Marches stop at |bound|, within
/// which the differences built with P.keep are exact.
Eigen::Vector3d marchFromPairs(std::vector<PairInfo>& pairs, Pieces& P, std::vector<Difference>& diffs, int deepest,
                               const Eigen::Vector3d& bound, double tol) {
  Eigen::Vector3d best = bound;
  double bestLength = bound.norm();
  const auto tryPair = [&](int k) {
    const SignedDistanceResult& r = pairs[static_cast<std::size_t>(k)].result;
    const Eigen::Vector3d x = r.distance * r.normal;
    const double r0 = x.norm();
    const Eigen::Vector3d u = r0 > tol ? Eigen::Vector3d(x / r0) : Eigen::Vector3d(-r.normal);
    const double t = marchOut(pairs, P, diffs, u, r0, bestLength, tol);
    if (t < bestLength && !P.exhausted) {  // (a march past an unbuilt difference proves nothing)
      bestLength = t;
      best = t * u;
    }
  };
  tryPair(deepest);
  for (int k = 0; k < static_cast<int>(pairs.size()) && !P.exhausted; ++k) {
    if (k != deepest && pairs[static_cast<std::size_t>(k)].result.distance < 0) tryPair(k);
  }
  return best;
}

/// True when the point x (in P) is strictly inside the difference of some pair other than
/// `skip`, decided by the pair's own signed distance with B moved by -x.
bool coveredByPairs(const std::vector<PairInfo>& pairs, int skip, int nB, const std::vector<PosedPiece>& A,
                    const std::vector<PosedPiece>& B, const Eigen::Vector3d& x, double tol,
                    const PenetrationOptions& options) {
  const double r = x.norm();
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    if (k == skip || pairs[static_cast<std::size_t>(k)].distanceLower >= r) continue;
    const PosedPiece& a = A[static_cast<std::size_t>(k / nB)];
    const PosedPiece& b = B[static_cast<std::size_t>(k % nB)];
    Eigen::Isometry3d X_moved = b.X_PP;
    X_moved.translation() -= x;
    if (signedDistance(*a.core, a.X_PP, *b.core, X_moved, nullptr, options).distance < -tol) return true;
  }
  return false;
}

/// The answer x (a point of the complement, in P) in `out`: distance, normal, bracket, and the
/// pieces and witnesses of the difference holding it (`holder`, or when -1 the one whose boundary
/// is nearest x: a march's end lies on the difference it left last). depthLower there is
/// `lowerBound`; the caller raises it by the pairwise one.
void setAnswer(const Eigen::Vector3d& x, int holder, BodyDepthStatus status, double lowerBound,
               const std::vector<Difference>& diffs, const Pieces& P, const Eigen::Vector3d& p_WP,
               BodySignedDistanceResult& out) {
  const double depth = x.norm();
  out.status = status;
  out.certified = status == BodyDepthStatus::Certified;
  out.distance = -depth;
  if (depth > 0) out.normal = -x / depth;  // else the deepest pair's, already in out
  out.depthUpper = depth;
  out.depthLower = std::min(depth, lowerBound);
  out.differences = static_cast<int>(diffs.size());
  double closest = std::numeric_limits<double>::infinity();
  for (int k = 0; holder < 0 && k < static_cast<int>(diffs.size()); ++k) {
    const double e = std::abs(body::planeExcess(diffs[static_cast<std::size_t>(k)], x));
    if (e < closest) closest = e, holder = k;
  }
  if (holder >= 0) {
    out.pieceA = diffs[static_cast<std::size_t>(holder)].pieceA;
    out.pieceB = diffs[static_cast<std::size_t>(holder)].pieceB;
  }
  setWitnesses(P.A[static_cast<std::size_t>(out.pieceA)], P.B[static_cast<std::size_t>(out.pieceB)], x, p_WP, out);
}

/// Steps 3 and 4 of the header's method, when the deepest pair's point is covered: the upper bound
/// by the marches, the relevant differences, the search, and the answer in `out` (BuildLimit with
/// the best verified point when the budget cannot pay for the differences).
void searchAnswer(std::vector<PairInfo>& pairs, int nB, const std::vector<PosedPiece>& A,
                  const std::vector<PosedPiece>& B, int deepest, double tol, const BodyDepthOptions& options,
                  const Eigen::Vector3d& p_WP, BodySignedDistanceResult& out) {
  // Every point the search asks about is within the bounding boxes' separation R, so facets
  // beyond R are left out of the differences; the margin (1e4 tol) keeps them out of every
  // membership test there, and above the round-off between near-parallel candidate normals.
  const Eigen::Vector3d bound = boxSeparation(A, B);
  Pieces P{A, B, nB, bound.norm() + 1e4 * tol, options.maxBuildCost};
  std::vector<Difference> diffs;
  const Eigen::Vector3d start = marchFromPairs(pairs, P, diffs, deepest, bound, tol);
  const double upper = start.norm();
  for (int k = 0; k < static_cast<int>(pairs.size()) && !P.exhausted; ++k) {
    if (pairs[static_cast<std::size_t>(k)].distanceLower < upper) ensureDifference(pairs, k, P, diffs);
  }
  if (P.exhausted) {
    setAnswer(start, -1, BodyDepthStatus::BuildLimit, 0.0, diffs, P, p_WP, out);
    return;
  }
  // The search asks only about points within the start's distance: the same rule, tighter.
  for (Difference& d : diffs) body::dropFacetsBeyond(d, upper + 1e4 * tol);
  // The box's point is often the answer itself (a push straight along an axis): the search then
  // also takes a face's point as near, up to tol, so that the answer names the face's pieces
  // rather than whichever difference's boundary is nearest the box's point.
  const double reach = start == bound ? upper + tol : upper;
  const body::SearchResult s = body::searchNearestBoundary(diffs, start, reach, options.maxFaces, tol);
  setAnswer(s.point, s.difference, s.finished ? BodyDepthStatus::Certified : BodyDepthStatus::FaceLimit, s.lowerBound,
            diffs, P, p_WP, out);
  out.facesSearched = s.facesSearched;
}

/// What step 1 found: the nearest pair (the deepest when some overlap), how many overlap, and
/// the largest pairwise depth lower bound.
struct PairCounts {
  int nearest = 0;
  int overlapping = 0;
  double depthLower = 0.0;
};

/// Step 1: each pair's signed distance, where it can matter. A pair whose pieces' bounding spheres
/// are apart cannot overlap; its distance is computed only when no pair overlaps and it may be the
/// nearest, and is otherwise bounded from below by the spheres' gap (distanceLower), which is all
/// the later steps ask of a pair that does not overlap.
PairCounts measurePairs(const std::vector<PosedPiece>& A, const std::vector<PosedPiece>& B,
                        const PenetrationOptions& options, std::vector<PairInfo>& pairs) {
  const std::size_t nB = B.size();
  std::vector<double> gap(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const PosedPiece& a = A[k / nB];
    const PosedPiece& b = B[k % nB];
    gap[k] = (a.X_PP * a.core->center() - b.X_PP * b.core->center()).norm() - a.core->boundingRadius() -
             b.core->boundingRadius();
  }
  PairCounts out;
  double nearestDistance = std::numeric_limits<double>::infinity();
  const auto measure = [&](std::size_t k) {
    PairInfo& p = pairs[k];
    p.result = signedDistance(*A[k / nB].core, A[k / nB].X_PP, *B[k % nB].core, B[k % nB].X_PP, nullptr, options);
    const bool converged = p.result.status != SignedDistanceStatus::NotConverged;
    p.distanceLower = p.result.distance > 0 && converged ? p.result.distance : 0.0;
    if (p.result.distance < 0) {
      ++out.overlapping;
      out.depthLower = std::max(out.depthLower, p.result.depthLower);
    }
    if (p.result.distance < nearestDistance) {
      nearestDistance = p.result.distance;
      out.nearest = static_cast<int>(k);
    }
  };
  std::vector<std::size_t> apart;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (gap[k] > 0.0) {
      apart.push_back(k);
      pairs[k].result.distance = gap[k];  // a lower bound until measured: the pair does not overlap
      pairs[k].distanceLower = gap[k];
    } else {
      measure(k);
    }
  }
  if (out.overlapping > 0) return out;
  std::sort(apart.begin(), apart.end(), [&](std::size_t i, std::size_t j) { return gap[i] < gap[j]; });
  for (std::size_t k : apart) {
    if (gap[k] >= nearestDistance) break;
    measure(k);
  }
  return out;
}

}  // namespace

BodySignedDistanceResult bodySignedDistance(const Body& bodyA, const Eigen::Isometry3d& X_WA, const Body& bodyB,
                                            const Eigen::Isometry3d& X_WB, const BodyDepthOptions& options) {
  checkBody(bodyA, X_WA, "A");
  checkBody(bodyB, X_WB, "B");
  if (!(options.maxBuildCost >= 0.0)) {
    std::ostringstream msg;
    msg << "bodySignedDistance: maxBuildCost must be >= 0 (microseconds; infinity for no cap), got "
        << options.maxBuildCost;
    throw std::invalid_argument(msg.str());
  }
  const Eigen::Vector3d p_WP = X_WA.translation();
  const std::vector<PosedPiece> A = posePieces(bodyA, X_WA, p_WP);
  const std::vector<PosedPiece> B = posePieces(bodyB, X_WB, p_WP);
  const int nB = static_cast<int>(B.size());
  const double tol = tol::kBodyMemberRelative * lengthScale(A, B);

  // 1. Every pair's own signed distance; the nearest pair and the deepest.
  std::vector<PairInfo> pairs(A.size() * B.size());
  const PairCounts counts = measurePairs(A, B, options.pair, pairs);
  const int nearest = counts.nearest;
  const int overlapping = counts.overlapping;
  const double depthLower = counts.depthLower;
  const SignedDistanceResult& deepest = pairs[static_cast<std::size_t>(nearest)].result;
  BodySignedDistanceResult out = fromPair(deepest, nearest / nB, nearest % nB, p_WP);
  out.overlappingPairs = overlapping;
  out.pairDepth = std::max(0.0, -deepest.distance);
  out.pairNormal = deepest.normal;
  if (overlapping == 0) {
    out.status = BodyDepthStatus::Separated;
    out.depthLower = out.depthUpper = -out.distance;
    return out;
  }

  // 2. The deepest pair's separating point: if no other pair covers it, it is the answer.
  const Eigen::Vector3d x0 = deepest.distance * deepest.normal;
  if (!coveredByPairs(pairs, nearest, nB, A, B, x0, tol, options.pair)) {
    out.status = deepest.certified ? BodyDepthStatus::Certified : BodyDepthStatus::PairNotCertified;
    out.certified = deepest.certified;
    out.depthLower = depthLower;
    out.depthUpper = -deepest.distance;
    return out;
  }

  // 3, 4. The upper bound, the relevant differences and the exact search.
  searchAnswer(pairs, nB, A, B, nearest, tol, options, p_WP, out);
  out.depthLower = std::max(out.depthLower, std::min(depthLower, out.depthUpper));
  return out;
}

}  // namespace deepcheck::geometry
