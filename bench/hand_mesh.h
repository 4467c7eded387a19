#pragma once
// A non-convex test mesh for the load benchmark: a gripper-like hand, a palm and four curled
// fingers, each a closed tube (a circle swept along a planar path, closed by cone caps),
// tessellated into about the number of triangles asked for. The fingers start inside the palm, so
// the mesh is five overlapping closed components, as hand meshes of CAD exports often are.

#include "deepcheck/robots/mesh.h"

namespace deepcheck::bench {

/// The hand, about 0.1 m across, in about `triangles` triangles (at least a few hundred).
robots::TriangleMesh handMesh(int triangles);

/// A harder hand: eight thinner fingers (radius 5 mm) curled by 200 degrees on the same palm,
/// which needs about twice the pieces.
robots::TriangleMesh combMesh(int triangles);

}  // namespace deepcheck::bench
