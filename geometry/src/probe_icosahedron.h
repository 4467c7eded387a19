#pragma once
// The probe directions of the certified method's start without GJK (certified_probe_start.cpp):
// the twelve vertices of a regular icosahedron in a generic orientation, with its twenty faces
// and their neighbours. Supports of M in these directions, joined as the icosahedron's faces, make
// the starting surface; a polytope stores its own supports in them (detail::probeSupport).

#include "deepcheck/geometry/internal/polytope_access.h"

#include <Eigen/Core>

namespace deepcheck::geometry::probe {

constexpr int kDirections = detail::kProbeDirections;
constexpr int kFaces = 20;

struct Icosahedron {
  Eigen::Vector3d direction[kDirections];  ///< unit vectors
  int opposite[kDirections];               ///< the index of -direction[i]
  int face[kFaces][3];                     ///< corners, counter-clockwise seen from outside
  int adj[kFaces][3];                      ///< neighbours, as ExpansionSurface::Face::adj
};

/// The icosahedron, built once (thread-safe).
const Icosahedron& icosahedron();

/// The rotation that puts probe directions in a generic orientation: none on a coordinate axis,
/// plane or box diagonal, where symmetric shapes put ties. The icosahedron's directions and the
/// certified expansion's four fallback directions (certified_expansion.cpp) are both turned by it.
const Eigen::Matrix3d& genericOrientation();

}  // namespace deepcheck::geometry::probe
