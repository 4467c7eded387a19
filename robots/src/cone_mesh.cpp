// The circumscribed pyramid of a cone, as a triangle mesh (moveit_scene.h).
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/moveit_scene.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {

TriangleMesh coneMesh(double height, double radius, double maxDeviation) {
  if (!(height > 0.0) || !std::isfinite(height) || !std::isfinite(radius)) {
    std::ostringstream msg;
    msg << "cone height " << height << " and radius " << radius << " must be positive and finite";
    throw std::invalid_argument(msg.str());
  }
  // Same number of sides as a cylinder of that radius: the base polygon's corners stick out of
  // the base circle by radius * (1 / cos(pi / N) - 1) <= maxDeviation (checks radius too).
  const int sides = cylinderSides(radius, maxDeviation);
  const double corner = radius / std::cos(M_PI / sides);
  TriangleMesh mesh;
  mesh.vertices.reserve(sides + 1);
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * M_PI * k / sides;
    mesh.vertices.emplace_back(corner * std::cos(angle), corner * std::sin(angle), -0.5 * height);
  }
  const int apex = sides;
  mesh.vertices.emplace_back(0.0, 0.0, 0.5 * height);
  // Counter-clockwise seen from outside: the sides go around +z, the base is seen from -z.
  for (int k = 0; k < sides; ++k) mesh.triangles.push_back({k, (k + 1) % sides, apex});
  for (int k = 1; k + 1 < sides; ++k) mesh.triangles.push_back({0, k + 1, k});
  return mesh;
}

}  // namespace deepcheck::robots
