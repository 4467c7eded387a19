#pragma once
// The triangle meshes robots reads (mesh_loader.h) and makes into pieces (collision_geometry.h)
// are the convex decomposition's (deepcheck/decomposition/mesh.h).

#include "deepcheck/decomposition/mesh.h"

namespace deepcheck::robots {

using decomposition::TriangleMesh;

}  // namespace deepcheck::robots
