// Reading the input of `deepcheck pd` (pd_input.h; the format is described in pd.cpp).

#include "pd_input.h"

#include "common.h"

#include "deepcheck/geometry/input_range.h"
#include "deepcheck/geometry/pair_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

/// Quaternions are taken as given, not silently repaired: one whose norm differs from 1 by more
/// than this is an input error. Within it (printed values carry a few digits) it is normalized so
/// that the pose is a rotation to round-off.
constexpr double kQuaternionNormTolerance = 1e-6;

int parsePointCount(const InputLine& line, const std::string& token) {
  const bool digits = !token.empty() && token.size() <= 9 && token.find_first_not_of("0123456789") == std::string::npos;
  const int n = digits ? std::atoi(token.c_str()) : 0;
  if (n < 1) failAt(line, "the point count '" + token + "' is not a positive integer");
  if (n > kMaxShapePoints) {
    failAt(line, "the point count " + token + " exceeds the supported " + std::to_string(kMaxShapePoints) +
                     " points per shape");
  }
  return n;
}

Eigen::Isometry3d parsePose(const InputLine& line, std::size_t first, const std::string& which) {
  double v[7];
  for (int i = 0; i < 7; ++i) v[i] = parseNumber(line, line.tokens[first + i]);
  Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  const double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= kQuaternionNormTolerance)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", norm);
    failAt(line, "the quaternion of " + which + " has norm " + buf +
                     " (must be 1 within 1e-6; quaternions are not normalized for you)");
  }
  q.coeffs() /= norm;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  try {
    geometry::checkPose(X, which.c_str());
  } catch (const std::exception& e) {
    failAt(line, e.what());
  }
  return X;
}

int shapeIndex(const PdInput& input, const InputLine& line, const std::string& id) {
  const auto it = input.ids.find(id);
  if (it == input.ids.end()) failAt(line, "unknown shape id '" + id + "'");
  return it->second;
}

/// Fails when `id` already names a shape or a body.
void rejectDuplicateId(const PdInput& input, const InputLine& line, const std::string& id) {
  if (const auto it = input.ids.find(id); it != input.ids.end()) {
    failAt(line, "duplicate id '" + id + "' (a shape defined on line " +
                     std::to_string(input.shapes[static_cast<std::size_t>(it->second)].line) + ")");
  }
  if (const auto it = input.bodyIds.find(id); it != input.bodyIds.end()) {
    failAt(line, "duplicate id '" + id + "' (a body defined on line " +
                     std::to_string(input.bodies[static_cast<std::size_t>(it->second)].line) + ")");
  }
}

/// A query side's id: a shape (returns its index, body = -1) or a body (returns -1, body set).
int sideIndex(const PdInput& input, const InputLine& line, const std::string& id, int& body) {
  body = -1;
  if (const auto it = input.bodyIds.find(id); it != input.bodyIds.end()) {
    body = it->second;
    return -1;
  }
  if (input.ids.find(id) == input.ids.end()) failAt(line, "unknown shape or body id '" + id + "'");
  return shapeIndex(input, line, id);
}

void readBody(const InputLine& line, PdInput& input) {
  if (line.tokens.size() < 2) failAt(line, "expected 'body <id> <shapeId> <shapeId> ...'");
  const std::string& id = line.tokens[1];
  if (line.tokens.size() < 3) failAt(line, "body '" + id + "' names no shape (a body needs at least one)");
  rejectDuplicateId(input, line, id);
  PdBody body{{}, line.number};
  for (std::size_t i = 2; i < line.tokens.size(); ++i) {
    const std::string& shape = line.tokens[i];
    if (input.bodyIds.count(shape) != 0) {
      failAt(line, "'" + shape + "' is a body; a body is made of shapes given before it");
    }
    const int index = shapeIndex(input, line, shape);
    if (std::find(body.shapes.begin(), body.shapes.end(), index) != body.shapes.end()) {
      failAt(line, "shape '" + shape + "' appears twice in body '" + id + "'");
    }
    body.shapes.push_back(index);
  }
  input.bodies.push_back(std::move(body));
  input.bodyIds.emplace(id, static_cast<int>(input.bodies.size()) - 1);
}

/// Reads the points of the shape whose header is `header` (`line` holds the line after it) and
/// builds its hull; on return `line` holds the line after the points and the result says whether
/// there is one.
bool readShape(std::istream& in, int& lineNumber, const InputLine& header, InputLine& line, PdInput& input) {
  if (header.tokens.size() != 3) failAt(header, "expected 'shape <id> <n>'");
  const std::string id = header.tokens[1];
  const int n = parsePointCount(header, header.tokens[2]);
  rejectDuplicateId(input, header, id);
  std::vector<Eigen::Vector3d> points;
  // A bad count must not allocate a huge buffer up front; the vector grows as points come.
  points.reserve(static_cast<std::size_t>(std::min(n, 1 << 16)));
  bool pending = nextInputLine(in, lineNumber, line);
  while (static_cast<int>(points.size()) < n) {
    if (!pending) {
      failAt(header, "shape '" + id + "' declares " + std::to_string(n) + " points but the input ends after " +
                         std::to_string(points.size()));
    }
    if (line.tokens[0] == "shape" || line.tokens[0] == "query" || line.tokens[0] == "body") {
      failAt(line, "shape '" + id + "' (line " + std::to_string(header.number) + ") declares " + std::to_string(n) +
                       " points but only " + std::to_string(points.size()) + " precede this line");
    }
    if (line.tokens.size() != 3) {
      failAt(line, "expected a point '<x> <y> <z>' (point " + std::to_string(points.size() + 1) + " of " +
                       std::to_string(n) + " of shape '" + id + "')");
    }
    Eigen::Vector3d p;
    for (int c = 0; c < 3; ++c) {
      p[c] = parseNumber(line, line.tokens[static_cast<std::size_t>(c)]);
      try {
        geometry::range::checkCoordinate(p[c], "'" + line.tokens[static_cast<std::size_t>(c)] + "'");
      } catch (const std::exception& e) {
        failAt(line, e.what());
      }
    }
    points.push_back(p);
    pending = nextInputLine(in, lineNumber, line);
  }
  try {
    input.shapes.push_back({geometry::ConvexPolytope::fromPoints(points, "shape '" + id + "'"), header.number});
  } catch (const std::exception& e) {
    failAt(header, "cannot build the hull of shape '" + id + "': " + e.what());
  }
  input.ids.emplace(id, static_cast<int>(input.shapes.size()) - 1);
  return pending;
}

PdQuery readQuery(const InputLine& line, const PdInput& input) {
  if (line.tokens.size() != 17) {
    failAt(line,
           "expected 'query <idA> <tx> <ty> <tz> <qw> <qx> <qy> <qz> <idB> <tx> <ty> <tz> "
           "<qw> <qx> <qy> <qz>' (17 fields, got " +
               std::to_string(line.tokens.size()) + ")");
  }
  PdQuery q;
  q.line = line.number;
  q.a = sideIndex(input, line, line.tokens[1], q.bodyA);
  q.X_WA = parsePose(line, 2, std::string("A (") + (q.bodyA < 0 ? "shape" : "body") + " '" + line.tokens[1] + "')");
  q.b = sideIndex(input, line, line.tokens[9], q.bodyB);
  q.X_WB = parsePose(line, 10, std::string("B (") + (q.bodyB < 0 ? "shape" : "body") + " '" + line.tokens[9] + "')");
  return q;
}

}  // namespace

PdInput readPdInput(std::istream& in) {
  PdInput input;
  int lineNumber = 0;
  InputLine line;
  bool pending = nextInputLine(in, lineNumber, line);
  while (pending) {
    const std::string& keyword = line.tokens[0];
    if (keyword == "shape") {
      const InputLine header = line;
      pending = readShape(in, lineNumber, header, line, input);
      continue;  // `line` already holds the next line
    }
    if (keyword == "query") {
      input.queries.push_back(readQuery(line, input));
    } else if (keyword == "body") {
      readBody(line, input);
    } else {
      failAt(line, "unknown keyword '" + keyword + "' (expected 'shape', 'body' or 'query')");
    }
    pending = nextInputLine(in, lineNumber, line);
  }
  return input;
}

geometry::Body queryBody(const PdInput& input, int shape, int body) {
  geometry::Body out;
  const auto piece = [&](int s) {
    out.pieces.push_back(
        {geometry::ConvexShape{&input.shapes[static_cast<std::size_t>(s)].hull, 0.0}, Eigen::Isometry3d::Identity()});
  };
  if (body < 0) piece(shape);
  else
    for (const int s : input.bodies[static_cast<std::size_t>(body)].shapes) piece(s);
  return out;
}

}  // namespace deepcheck::tools
