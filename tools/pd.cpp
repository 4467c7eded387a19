// `deepcheck pd`: signed distance / penetration depth of posed convex shapes read from stdin.
// The input and output formats are a contract (DESIGN.md, "The deepcheck tool"):
//
//   shape <id> <n>          followed by n lines "<x> <y> <z>": the shape is their convex hull
//   query <idA> <tx> <ty> <tz> <qw> <qx> <qy> <qz> <idB> <tx> <ty> <tz> <qw> <qx> <qy> <qz>
//   # comment               (lines whose first non-blank character is '#'; blank lines too)
//
// Output: one line per query on stdout, "sd nx ny nz" with %.17g (sd > 0 distance, sd < 0 minus
// the penetration depth, n the unit normal from A towards B, world frame); on stderr a last line
// "queries N total_us T", T the time spent in the signed-distance calls only, in whole
// microseconds (parsing and hull building excluded).
//
// The whole input is parsed and every hull built before the first query runs, so a bad input
// produces no output on stdout, only one error line (naming the input line) and exit status 1.

#include "common.h"
#include "subcommands.h"

#include "deepcheck/deep/exact.h"
#include "deepcheck/deep/signed_distance.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

using deep::ConvexPolytope;

/// Quaternions are taken as given, not silently repaired: one whose norm differs from 1 by more
/// than this is an input error. Within it (printed values carry a few digits) it is normalized so
/// that the pose is a rotation to round-off.
constexpr double kQuaternionNormTolerance = 1e-6;

constexpr const char* kUsage =
    "usage: deepcheck pd [--cold] [--exact] < cases.txt\n"
    "\n"
    "Signed distance of pairs of posed convex shapes. Input on stdin:\n"
    "  shape <id> <n>      followed by n lines '<x> <y> <z>' (the shape is their convex hull)\n"
    "  query <idA> <tx> <ty> <tz> <qw> <qx> <qy> <qz> <idB> <tx> <ty> <tz> <qw> <qx> <qy> <qz>\n"
    "  lines starting with '#' are comments; blank lines are ignored.\n"
    "Output: one line 'sd nx ny nz' per query (sd < 0: penetration depth; n from A to B),\n"
    "and on stderr a last line 'queries N total_us T' (time in the queries only).\n"
    "\n"
    "options:\n"
    "  --cold    no warm start (by default consecutive queries of the same pair share a cache)\n"
    "  --exact   answer with the exact brute-force reference (hull of all vertex differences)\n";

int parsePointCount(const InputLine& line, const std::string& token) {
  const bool digits = !token.empty() && token.size() <= 9 &&
                      token.find_first_not_of("0123456789") == std::string::npos;
  const int n = digits ? std::atoi(token.c_str()) : 0;
  if (n < 1) failAt(line, "the point count '" + token + "' is not a positive integer");
  return n;
}

struct Shape {
  ConvexPolytope hull;
  int line;
};

struct Query {
  int line;
  int a;
  int b;
  Eigen::Isometry3d X_WA;
  Eigen::Isometry3d X_WB;
};

struct Input {
  std::vector<Shape> shapes;
  std::map<std::string, int> ids;  // shape id -> index in shapes
  std::vector<Query> queries;
};

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
  return X;
}

int shapeIndex(const Input& input, const InputLine& line, const std::string& id) {
  const auto it = input.ids.find(id);
  if (it == input.ids.end()) failAt(line, "unknown shape id '" + id + "'");
  return it->second;
}

Input readInput(std::istream& in) {
  Input input;
  int lineNumber = 0;
  InputLine line;
  bool pending = nextInputLine(in, lineNumber, line);
  while (pending) {
    const std::string& keyword = line.tokens[0];
    if (keyword == "shape") {
      if (line.tokens.size() != 3) failAt(line, "expected 'shape <id> <n>'");
      const InputLine header = line;
      const std::string id = header.tokens[1];
      const int n = parsePointCount(header, header.tokens[2]);
      if (const auto it = input.ids.find(id); it != input.ids.end()) {
        failAt(header, "duplicate shape id '" + id + "' (first defined on line " +
                         std::to_string(input.shapes[static_cast<std::size_t>(it->second)].line) +
                         ")");
      }
      std::vector<Eigen::Vector3d> points;
      // A bad count must not allocate a huge buffer up front; the vector grows as points come.
      points.reserve(static_cast<std::size_t>(std::min(n, 1 << 16)));
      pending = nextInputLine(in, lineNumber, line);
      while (static_cast<int>(points.size()) < n) {
        if (!pending) {
          failAt(header, "shape '" + id + "' declares " + std::to_string(n) +
                           " points but the input ends after " + std::to_string(points.size()));
        }
        if (line.tokens[0] == "shape" || line.tokens[0] == "query") {
          failAt(line, "shape '" + id + "' (line " + std::to_string(header.number) + ") declares " +
                         std::to_string(n) + " points but only " + std::to_string(points.size()) +
                         " precede this line");
        }
        if (line.tokens.size() != 3) {
          failAt(line, "expected a point '<x> <y> <z>' (point " + std::to_string(points.size() + 1) +
                         " of " + std::to_string(n) + " of shape '" + id + "')");
        }
        points.emplace_back(parseNumber(line, line.tokens[0]), parseNumber(line, line.tokens[1]),
                            parseNumber(line, line.tokens[2]));
        pending = nextInputLine(in, lineNumber, line);
      }
      try {
        input.shapes.push_back({ConvexPolytope::fromPoints(points, "shape '" + id + "'"),
                                header.number});
      } catch (const std::exception& e) {
        failAt(header, "cannot build the hull of shape '" + id + "': " + e.what());
      }
      input.ids.emplace(id, static_cast<int>(input.shapes.size()) - 1);
      continue;  // `line` already holds the next line
    }
    if (keyword == "query") {
      if (line.tokens.size() != 17) {
        failAt(line, "expected 'query <idA> <tx> <ty> <tz> <qw> <qx> <qy> <qz> <idB> <tx> <ty> <tz> "
                   "<qw> <qx> <qy> <qz>' (17 fields, got " +
                       std::to_string(line.tokens.size()) + ")");
      }
      Query q;
      q.line = line.number;
      q.a = shapeIndex(input, line, line.tokens[1]);
      q.X_WA = parsePose(line, 2, "A (shape '" + line.tokens[1] + "')");
      q.b = shapeIndex(input, line, line.tokens[9]);
      q.X_WB = parsePose(line, 10, "B (shape '" + line.tokens[9] + "')");
      input.queries.push_back(q);
    } else {
      failAt(line, "unknown keyword '" + keyword + "' (expected 'shape' or 'query')");
    }
    pending = nextInputLine(in, lineNumber, line);
  }
  return input;
}

int runPd(std::vector<std::string> args) {
  const bool cold = takeFlag(args, "--cold");
  const bool exact = takeFlag(args, "--exact");
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args[0] + "' (input is read from stdin)");

  std::ios::sync_with_stdio(false);
  const Input input = readInput(std::cin);

  deep::PairCache cache;
  int lastA = -1;
  int lastB = -1;
  std::chrono::steady_clock::duration total{0};
  for (const Query& q : input.queries) {
    const ConvexPolytope& A = input.shapes[static_cast<std::size_t>(q.a)].hull;
    const ConvexPolytope& B = input.shapes[static_cast<std::size_t>(q.b)].hull;
    // Warm start only across consecutive queries of the same ordered pair.
    if (q.a != lastA || q.b != lastB) cache.reset();
    lastA = q.a;
    lastB = q.b;
    double sd = 0.0;
    Eigen::Vector3d n;
    try {
      if (exact) {
        const auto t0 = std::chrono::steady_clock::now();
        const deep::ExactResult r = deep::exactSignedDistance(A, q.X_WA, B, q.X_WB);
        total += std::chrono::steady_clock::now() - t0;
        sd = r.distance;
        n = r.normal;
      } else {
        const auto t0 = std::chrono::steady_clock::now();
        const deep::SignedDistanceResult r =
            deep::signedDistance(A, q.X_WA, B, q.X_WB, cold ? nullptr : &cache);
        total += std::chrono::steady_clock::now() - t0;
        sd = r.distance;
        n = r.normal;
      }
    } catch (const std::exception& e) {
      std::fflush(stdout);
      throw InputError("query on line " + std::to_string(q.line) + ": " + e.what());
    }
    std::printf("%.17g %.17g %.17g %.17g\n", sd, n.x(), n.y(), n.z());
  }
  std::fflush(stdout);
  const long long micros = static_cast<long long>(
      std::llround(std::chrono::duration<double, std::micro>(total).count()));
  std::fprintf(stderr, "queries %zu total_us %lld\n", input.queries.size(), micros);
  return 0;
}

}  // namespace

const Subcommand kPdCommand = {"pd", "signed distance / penetration depth of posed convex shapes",
                               kUsage, runPd};

}  // namespace deepcheck::tools
