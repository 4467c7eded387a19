#pragma once
// The input of `deepcheck pd` (its format: tools/pd.cpp), read by `deepcheck pd` and
// `deepcheck view --pd`: shapes, built into hulls, and posed queries.

#include "deepcheck/deep/polytope.h"

#include <Eigen/Geometry>

#include <istream>
#include <map>
#include <string>
#include <vector>

namespace deepcheck::tools {

struct PdShape {
  deep::ConvexPolytope hull;
  int line;  ///< line of its 'shape' header
};

struct PdQuery {
  int line;
  int a;  ///< index in PdInput::shapes
  int b;
  Eigen::Isometry3d X_WA;
  Eigen::Isometry3d X_WB;
};

struct PdInput {
  std::vector<PdShape> shapes;
  std::map<std::string, int> ids;  ///< shape id -> index in shapes
  std::vector<PdQuery> queries;
};

/// Largest point count of one shape. Building the hull of this many points (Qhull, then deep's
/// own merging, pruning and checks) takes seconds in an optimized build and minutes under
/// AddressSanitizer; larger point clouds should be reduced (e.g. to their hull vertices, or by
/// deepcheck decompose) before being given.
constexpr int kMaxShapePoints = 100000;

/// Parses the whole input and builds every hull. Throws InputError naming the line on bad input
/// (syntax, unknown or duplicate ids, non-unit quaternions, values outside deep's supported
/// range, hulls that cannot be built).
PdInput readPdInput(std::istream& in);

}  // namespace deepcheck::tools
