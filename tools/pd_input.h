#pragma once
// The input of `deepcheck pd` (its format: tools/pd.cpp), read by `deepcheck pd` and
// `deepcheck view --pd`.

#include "common.h"

#include "deepcheck/deep/polytope.h"

#include <Eigen/Geometry>

#include <istream>
#include <map>
#include <string>
#include <vector>

namespace deepcheck::tools {

struct PdShape {
  deep::ConvexPolytope hull;
  int line;
};

struct PdQuery {
  int line;
  int a;  ///< index into PdInput::shapes
  int b;
  Eigen::Isometry3d X_WA;
  Eigen::Isometry3d X_WB;
};

struct PdInput {
  std::vector<PdShape> shapes;
  std::map<std::string, int> ids;  ///< shape id -> index in shapes
  std::vector<PdQuery> queries;
};

/// Reads the whole input, building every hull; throws InputError naming the line.
PdInput readPdInput(std::istream& in);

}  // namespace deepcheck::tools
