#pragma once
// Internal to deepcheck::decomposition: the concavity of a hull, by sampling its surface
// (concavity.cpp).

#include "bvh.h"
#include "cross_section.h"
#include "hull.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace deepcheck::decomposition::detail {

/// What a hull is measured against: the union of some parts' triangles (optionally clipped by a
/// half-space), and the cut planes whose cross-sections say where the plane is inside the solid.
struct Cap {
  Vector3d normal;
  double offset;
  const CrossSection* section;
};

struct Target {
  const TriangleBvh* mesh = nullptr;  ///< the whole mesh's triangles
  std::vector<Cap> caps;
};

struct Concavity {
  double value = 0.0;
  bool aborted = false;  ///< stopped once value exceeded the caller's bound
  bool hasWorst = false;
  Vector3d worstSample = Vector3d::Zero();
  Vector3d worstNearest = Vector3d::Zero();  ///< the mesh point nearest to worstSample
};

/// Which fixed points of the hull's triangles are sampled besides the random ones.
enum class Extra {
  None,   ///< random samples only (candidate cuts, which are many)
  Dense,  ///< each triangle's centroid and edge midpoints (parts, merges, the final report):
          ///< catches thin slivers of hull and maxima on hull edges
};

/// Samples `count` random points on the surface of `hull` (area-weighted), plus the `extra`
/// points, and returns the largest distance to `target`.
/// Stops as soon as the largest distance exceeds `abortAbove` (aborted = true).
Concavity measureConcavity(const Hull& hull, const Target& target, int count, Extra extra, std::uint64_t seed,
                           double abortAbove, double diagonal, const Vector3d* hint = nullptr);

}  // namespace deepcheck::decomposition::detail
