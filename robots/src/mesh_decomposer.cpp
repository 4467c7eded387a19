// The decomposer a robot's meshes are made into pieces with (collision_geometry.h): the convex
// decomposition through its on-disk cache, or one hull per mesh.

#include "deepcheck/robots/collision_geometry.h"

#include "deepcheck/decomposition/cache.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace deepcheck::robots {

MeshDecomposer meshDecomposer(const DecomposerOptions& options, std::shared_ptr<double> largestConcavity) {
  if (!options.decompose) {
    return [largestConcavity](const TriangleMesh& mesh) {
      // One hull: how far it sticks out of the mesh is not measured.
      if (largestConcavity) *largestConcavity = std::numeric_limits<double>::quiet_NaN();
      return convexHullDecomposer(mesh);
    };
  }
  options.parameters.validate();
  const decomposition::DecompositionParams params = options.parameters;
  const decomposition::DecompositionCache cache(options.cacheDir);
  return [params, cache, largestConcavity = std::move(largestConcavity)](const TriangleMesh& mesh) {
    const decomposition::ConvexDecomposition d = decomposition::decomposeConvexCached(mesh, params, cache);
    if (largestConcavity && !std::isnan(*largestConcavity)) {
      *largestConcavity = std::max(*largestConcavity, d.report.concavity);
    }
    return d.polytopes();
  };
}

}  // namespace deepcheck::robots
