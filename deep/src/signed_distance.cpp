#include "deepcheck/deep/signed_distance.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deepcheck::deep {

const char* toString(SignedDistanceStatus s) {
  switch (s) {
    case SignedDistanceStatus::Separated: return "separated";
    case SignedDistanceStatus::Penetrating: return "penetrating";
    case SignedDistanceStatus::NotConverged: return "not-converged";
  }
  return "unknown";
}

namespace {

void checkShape(const ConvexShape& s, const char* which) {
  if (s.core == nullptr) throw std::invalid_argument(std::string("signedDistance: shape ") + which + " has no core polytope");
  if (!std::isfinite(s.radius) || s.radius < 0) {
    std::ostringstream msg;
    msg << "signedDistance: shape " << which << " has an invalid radius " << s.radius
        << " (must be finite and >= 0)";
    throw std::invalid_argument(msg.str());
  }
}

/// Feature of polytope P touched by a GJK simplex (its distinct vertex indices).
Feature simplexFeature(const ConvexPolytope& P, const int* idx, int n, const Eigen::Vector3d& outward_P,
                       const Eigen::Matrix3d& R_PtoP) {
  int distinct[4];
  int m = 0;
  for (int i = 0; i < n; ++i) {
    bool seen = false;
    for (int j = 0; j < m; ++j) seen = seen || distinct[j] == idx[i];
    if (!seen) distinct[m++] = idx[i];
  }
  Feature f;
  if (m == 1) {
    f.type = Feature::Type::Vertex;
    f.index = distinct[0];
  } else if (m == 2) {
    f.type = Feature::Type::Edge;
    f.index = distinct[0];
    f.index2 = distinct[1];
  } else {
    // A face: the ring face of the first vertex whose normal best matches the outward direction.
    f.type = Feature::Type::Face;
    f.index = -1;
    double bestDot = -2;
    const Eigen::Vector3d dirLocal = R_PtoP.transpose() * outward_P;
    for (int face : P.vertexFaces(distinct[0])) {
      const double d = P.faceNormal(face).dot(dirLocal);
      if (d > bestDot) {
        bestDot = d;
        f.index = face;
      }
    }
    if (f.index < 0) {
      f.type = Feature::Type::Vertex;
      f.index = distinct[0];
    }
  }
  return f;
}

Feature deepFeatureA(const DeepResult& d) {
  Feature f;
  switch (d.type) {
    case DeepResult::FacetType::VF: f.type = Feature::Type::Vertex; f.index = d.featureA; break;
    case DeepResult::FacetType::FV: f.type = Feature::Type::Face; f.index = d.featureA; break;
    case DeepResult::FacetType::EE: f.type = Feature::Type::Edge; f.index = d.featureA; f.index2 = d.featureA2; break;
  }
  return f;
}

Feature deepFeatureB(const DeepResult& d) {
  Feature f;
  switch (d.type) {
    case DeepResult::FacetType::VF: f.type = Feature::Type::Face; f.index = d.featureB; break;
    case DeepResult::FacetType::FV: f.type = Feature::Type::Vertex; f.index = d.featureB; break;
    case DeepResult::FacetType::EE: f.type = Feature::Type::Edge; f.index = d.featureB; f.index2 = d.featureB2; break;
  }
  return f;
}

}  // namespace

SignedDistanceResult signedDistance(const ConvexShape& A, const Eigen::Isometry3d& X_WA,
                                    const ConvexShape& B, const Eigen::Isometry3d& X_WB,
                                    PairCache* cache, const DeepOptions& options) {
  checkShape(A, "A");
  checkShape(B, "B");
  const ConvexPolytope& a = *A.core;
  const ConvexPolytope& b = *B.core;
  const PairFrame frame = PairFrame::make(a, X_WA, b, X_WB);

  SignedDistanceResult r;
  Eigen::Vector3d n_P, pA_P, pB_P;
  double coreSd;
  const GjkResult g = gjkDistance(a, b, frame, cache ? &cache->gjk : nullptr);
  const bool apart = g.status == GjkStatus::Separated ||
                     (g.status == GjkStatus::MaxIterations && g.distance > 0);
  if (apart) {
    coreSd = g.distance;
    n_P = g.normal;
    pA_P = g.pointA;
    pB_P = g.pointB;
    r.status = g.status == GjkStatus::Separated ? SignedDistanceStatus::Separated
                                                : SignedDistanceStatus::NotConverged;
    r.featureA = simplexFeature(a, g.simplexA.data(), g.simplexSize, n_P, Eigen::Matrix3d::Identity());
    r.featureB = simplexFeature(b, g.simplexB.data(), g.simplexSize, -n_P, frame.R);
    if (cache) cache->deep.valid = false;
  } else {
    const DeepResult d = deepPenetration(a, b, frame, cache ? &cache->deep : nullptr, options);
    coreSd = -d.depth;
    n_P = d.normal;
    pA_P = d.pointA;
    pB_P = d.pointB;
    r.status = d.status == DeepStatus::Converged ? SignedDistanceStatus::Penetrating
                                                 : SignedDistanceStatus::NotConverged;
    r.featureA = deepFeatureA(d);
    r.featureB = deepFeatureB(d);
    r.deep = d.stats;
  }
  // Radii: A grows towards B along n, B towards A along -n.
  r.distance = coreSd - A.radius - B.radius;
  r.normal = frame.X_WP.linear() * n_P;
  r.pointA = frame.X_WP * (pA_P + A.radius * n_P);
  r.pointB = frame.X_WP * (pB_P - B.radius * n_P);
  return r;
}

SignedDistanceResult signedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA,
                                    const ConvexPolytope& B, const Eigen::Isometry3d& X_WB,
                                    PairCache* cache, const DeepOptions& options) {
  return signedDistance(ConvexShape{&A, 0.0}, X_WA, ConvexShape{&B, 0.0}, X_WB, cache, options);
}

bool overlaps(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
              const Eigen::Isometry3d& X_WB, PairCache* cache) {
  checkShape(A, "A");
  checkShape(B, "B");
  checkPose(X_WA, "X_WA");
  checkPose(X_WB, "X_WB");
  return overlapsUnchecked(A, X_WA, B, X_WB, cache);
}

bool overlapsUnchecked(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                       const Eigen::Isometry3d& X_WB, PairCache* cache) {
  const PairFrame frame = PairFrame::makeUnchecked(*A.core, X_WA, *B.core, X_WB);
  if (A.radius == 0 && B.radius == 0) return gjkOverlap(*A.core, *B.core, frame, cache ? &cache->gjk : nullptr);
  const GjkResult g = gjkDistance(*A.core, *B.core, frame, cache ? &cache->gjk : nullptr);
  return g.distance <= A.radius + B.radius;
}

}  // namespace deepcheck::deep
