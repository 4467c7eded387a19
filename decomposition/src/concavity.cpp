// Concavity of a hull by surface sampling (concavity.h).

#include "concavity.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace deepcheck::decomposition::detail {

namespace {

/// The cap plane each hull triangle lies on (-1: none).
std::vector<int> capPlanes(const Hull& hull, const Target& target, double diagonal) {
  const int numTriangles = static_cast<int>(hull.triangles.size());
  std::vector<int> capOf(numTriangles, -1);
  for (int t = 0; t < numTriangles; ++t) {
    for (int c = 0; c < static_cast<int>(target.caps.size()); ++c) {
      const double cosine = hull.normals[t].dot(target.caps[c].normal);
      if (std::abs(cosine) < 1.0 - tol::kOnPlaneNormal) continue;
      const double offset = cosine > 0.0 ? target.caps[c].offset : -target.caps[c].offset;
      if (std::abs(hull.offsets[t] - offset) <= tol::kOnPlaneRelative * diagonal) {
        capOf[t] = c;
        break;
      }
    }
  }
  return capOf;
}

using Sample = std::pair<Vector3d, int>;  ///< a point and the hull triangle it lies on

/// The hull surface point nearest to the hint (where the parent's worst sample was), sampled
/// first: a concavity that survives a cut is found there even if the random samples miss it.
void addHintSample(const Hull& hull, const Vector3d& hint, std::vector<Sample>* samples) {
  double best = kInf;
  int bestTriangle = -1;
  Vector3d bestPoint = hint;
  for (int t = 0; t < static_cast<int>(hull.triangles.size()); ++t) {
    const auto& tri = hull.triangles[t];
    const Vector3d q =
        detail::closestPointOnTriangle(hint, hull.vertices[tri[0]], hull.vertices[tri[1]], hull.vertices[tri[2]]);
    const double d = (q - hint).squaredNorm();
    if (d < best) {
      best = d;
      bestTriangle = t;
      bestPoint = q;
    }
  }
  if (bestTriangle >= 0) samples->emplace_back(bestPoint, bestTriangle);
}

/// `count` random points of the hull's surface, area-weighted.
void addRandomSamples(const Hull& hull, int count, std::uint64_t seed, std::vector<Sample>* samples) {
  const int numTriangles = static_cast<int>(hull.triangles.size());
  std::vector<double> cumulative(numTriangles);
  double total = 0.0;
  for (int t = 0; t < numTriangles; ++t) {
    const auto& tri = hull.triangles[t];
    total +=
        0.5 *
        (hull.vertices[tri[1]] - hull.vertices[tri[0]]).cross(hull.vertices[tri[2]] - hull.vertices[tri[0]]).norm();
    cumulative[t] = total;
  }
  Rng rng(seed);
  for (int i = 0; i < count; ++i) {
    const double pick = rng.uniform() * total;
    const int t = std::min<int>(
        static_cast<int>(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
        numTriangles - 1);
    const auto& tri = hull.triangles[t];
    // Uniform point in a triangle: reflect the unit square's upper half onto the lower one.
    double a = rng.uniform();
    double b = rng.uniform();
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const Vector3d& p0 = hull.vertices[tri[0]];
    samples->emplace_back(p0 + a * (hull.vertices[tri[1]] - p0) + b * (hull.vertices[tri[2]] - p0), t);
  }
}

/// Extra::Dense: each triangle's centroid and edge midpoints.
void addDenseSamples(const Hull& hull, std::vector<Sample>* samples) {
  for (int t = 0; t < static_cast<int>(hull.triangles.size()); ++t) {
    const auto& tri = hull.triangles[t];
    const Vector3d& p0 = hull.vertices[tri[0]];
    const Vector3d& p1 = hull.vertices[tri[1]];
    const Vector3d& p2 = hull.vertices[tri[2]];
    samples->emplace_back((p0 + p1 + p2) / 3.0, t);
    samples->emplace_back(0.5 * (p0 + p1), t);
    samples->emplace_back(0.5 * (p1 + p2), t);
    samples->emplace_back(0.5 * (p2 + p0), t);
  }
}

/// Distance of a sample on hull triangle t to the target, or a value <= `floor` when it is known
/// not to exceed `floor` (then `nearest` is not set).
struct DistanceToTarget {
  const Target& target;
  const std::vector<int>& capOf;

  double operator()(const Vector3d& p, int t, double floor, Vector3d* nearest) const {
    if (capOf[t] >= 0 && target.caps[capOf[t]].section->contains(p)) return 0.0;  // inside
    Vector3d q;
    const double d = target.mesh->distance(p, nullptr, floor, &q);
    if (d > floor) *nearest = q;
    return d;
  }
};

/// Hill-climbs the distance from a seed sample within its hull triangle, halving the step when
/// no neighbour is farther; returns the largest distance found, `p` and `nearest` where.
double refineSample(const Hull& hull, const DistanceToTarget& distanceOf, int t, int steps, double diagonal,
                    Vector3d* p, Vector3d* nearest) {
  const auto& tri = hull.triangles[t];
  const Vector3d& a = hull.vertices[tri[0]];
  const Vector3d e1 = hull.vertices[tri[1]] - a;
  const Vector3d e2 = hull.vertices[tri[2]] - a;
  const Vector3d normal = e1.cross(e2);
  const double area2 = normal.squaredNorm();
  // Barycentric coordinates of x in the triangle, to stay inside it.
  auto inside = [&](const Vector3d& x) {
    const Vector3d r = x - a;
    const double u = r.cross(e2).dot(normal) / area2;
    const double v = e1.cross(r).dot(normal) / area2;
    return u >= 0.0 && v >= 0.0 && u + v <= 1.0;
  };
  const Vector3d ux = e1.normalized();
  const Vector3d uy = normal.cross(e1).normalized();
  double value = distanceOf(*p, t, 0.0, nearest);
  double step = 0.25 * std::sqrt(std::sqrt(area2));
  for (int iteration = 0; iteration < steps && step > tol::kOnPlaneRelative * diagonal; ++iteration) {
    bool moved = false;
    for (int dirIndex = 0; dirIndex < 6; ++dirIndex) {
      const double angle = dirIndex * kPi / 3.0;
      const Vector3d x = *p + step * (std::cos(angle) * ux + std::sin(angle) * uy);
      if (!inside(x)) continue;
      Vector3d q = x;
      const double d = distanceOf(x, t, value, &q);
      if (d > value) {
        value = d;
        *p = x;
        *nearest = q;
        moved = true;
      }
    }
    if (!moved) step *= 0.5;
  }
  return value;
}

/// Sets result to the new maximum (value, p, nearest); true when it exceeds `abortAbove`.
bool recordMaximum(Concavity* result, double value, const Vector3d& p, const Vector3d& nearest, double abortAbove) {
  result->value = value;
  result->hasWorst = std::isfinite(value);
  result->worstSample = p;
  result->worstNearest = nearest;
  result->aborted = result->value > abortAbove;
  return result->aborted;
}

}  // namespace

Concavity measureConcavity(const Hull& hull, const Target& target, int count, Extra extra, std::uint64_t seed,
                           double abortAbove, double diagonal, const Vector3d* hint) {
  Concavity result;
  const int numTriangles = static_cast<int>(hull.triangles.size());
  if (numTriangles == 0 || !(hull.area > 0.0)) return result;  // a segment or point: on the mesh
  const std::vector<int> capOf = capPlanes(hull, target, diagonal);
  std::vector<Sample> samples;
  samples.reserve(count + 1 + 4 * numTriangles);
  if (hint != nullptr) addHintSample(hull, *hint, &samples);
  addRandomSamples(hull, count, seed, &samples);
  if (extra != Extra::None) addDenseSamples(hull, &samples);
  const DistanceToTarget distanceOf{target, capOf};
  // Seeds for the refinement: the last few samples that raised the maximum.
  std::vector<Sample> seeds;
  for (const auto& [p, t] : samples) {
    Vector3d nearest = p;
    const double d = distanceOf(p, t, result.value, &nearest);
    if (d <= result.value) continue;
    seeds.emplace_back(p, t);
    if (recordMaximum(&result, d, p, nearest, abortAbove)) return result;
  }
  // Refinement: the maximum of the distance over a facet is usually a small spot (the middle of a
  // hole spanned by the hull) that a few random samples find only roughly. Hill-climb from the
  // last seeds within their hull triangles.
  const int refineSeeds = extra == Extra::None ? tol::kCandidateRefineSeeds : tol::kRefineSeeds;
  const int refineSteps = extra == Extra::None ? tol::kCandidateRefineSteps : tol::kRefineSteps;
  const int firstSeed = std::max(0, static_cast<int>(seeds.size()) - refineSeeds);
  for (int k = static_cast<int>(seeds.size()) - 1; k >= firstSeed; --k) {
    Vector3d p = seeds[k].first;
    const int t = seeds[k].second;
    const auto& tri = hull.triangles[t];
    const Vector3d e1 = hull.vertices[tri[1]] - hull.vertices[tri[0]];
    const Vector3d e2 = hull.vertices[tri[2]] - hull.vertices[tri[0]];
    if (!(e1.cross(e2).squaredNorm() > 0.0)) continue;
    Vector3d nearest = p;
    const double value = refineSample(hull, distanceOf, t, refineSteps, diagonal, &p, &nearest);
    if (value > result.value && recordMaximum(&result, value, p, nearest, abortAbove)) return result;
  }
  return result;
}

}  // namespace deepcheck::decomposition::detail
