#pragma once
// The input of `deepcheck pd` (its format: tools/pd.cpp), read by `deepcheck pd` and
// `deepcheck view --pd`: shapes, built into hulls, bodies (unions of shapes) and posed queries.

#include "deepcheck/geometry/body_depth.h"
#include "deepcheck/geometry/polytope.h"

#include <Eigen/Geometry>

#include <istream>
#include <map>
#include <string>
#include <vector>

namespace deepcheck::tools {

struct PdShape {
  geometry::ConvexPolytope hull;
  int line;  ///< line of its 'shape' header
};

/// A body: the union of shapes given before it, each in the body's frame.
struct PdBody {
  std::vector<int> shapes;  ///< indices in PdInput::shapes
  int line;                 ///< line of its 'body' line
};

struct PdQuery {
  int line;
  int a;           ///< index in PdInput::shapes, or -1 when A is a body
  int b;           ///< likewise for B
  int bodyA = -1;  ///< index in PdInput::bodies when A is a body, else -1
  int bodyB = -1;
  Eigen::Isometry3d X_WA;
  Eigen::Isometry3d X_WB;

  /// The query names a body on either side (it is then answered by geometry::bodySignedDistance).
  bool namesBody() const { return bodyA >= 0 || bodyB >= 0; }
};

struct PdInput {
  std::vector<PdShape> shapes;
  std::map<std::string, int> ids;  ///< shape id -> index in shapes
  std::vector<PdBody> bodies;
  std::map<std::string, int> bodyIds;  ///< body id -> index in bodies
  std::vector<PdQuery> queries;
};

/// The body one side of a query names: a body's shapes, or its one shape, each at the identity in
/// the body's frame. Points into input.shapes, which must outlive it.
geometry::Body queryBody(const PdInput& input, int shape, int body);

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
