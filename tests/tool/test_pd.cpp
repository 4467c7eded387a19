// End-to-end tests of `deepcheck pd` (and the dispatcher): the binary is run with popen on inputs
// written to temporary files; its answers are compared with the library called in-process.

#include "deepcheck/deep/exact.h"
#include "deepcheck/deep/signed_distance.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace deepcheck::deep;
namespace fs = std::filesystem;

namespace {

/// DEEP / GJK against the exact reference, relative to the pair's length scale: both are exact
/// up to round-off when the walk finds the global minimum, which it must on these inputs.
constexpr double kAgree = 1e-9;
/// Normals are compared only where they are well defined (|sd| not tiny), to this accuracy.
constexpr double kNormalAgree = 1e-6;
/// Warm and cold starts reach the same facet: the answers may differ by round-off only.
constexpr double kColdWarm = 1e-9;

struct Run {
  int status = -1;
  std::string out;
  std::string err;
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

fs::path tempPath(const std::string& what) {
  static int counter = 0;
  return fs::temp_directory_path() /
         ("deepcheck_tool_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" +
          what);
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `deepcheck <args>` with `input` on stdin.
Run runTool(const std::string& args, const std::string& input) {
  const fs::path in = tempPath("in.txt");
  const fs::path err = tempPath("err.txt");
  {
    std::ofstream f(in, std::ios::binary);
    f << input;
  }
  const std::string cmd = quote(DEEPCHECK_TOOL) + " " + args + " < " + quote(in.string()) + " 2> " +
                          quote(err.string());
  Run r;
  if (FILE* pipe = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
    const int status = ::pclose(pipe);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  r.err = readFile(err);
  fs::remove(in);
  fs::remove(err);
  return r;
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// One answer line "sd nx ny nz", parsed; checks that each field is printed with %.17g.
struct Answer {
  double sd = 0.0;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
};

Answer parseAnswer(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  std::string f;
  while (in >> f) fields.push_back(f);
  BOOST_TEST_REQUIRE(fields.size() == 4u, "answer line '" << line << "'");
  double v[4];
  for (int i = 0; i < 4; ++i) {
    v[i] = std::strtod(fields[i].c_str(), nullptr);
    BOOST_TEST(fmt(v[i]) == fields[i], "field printed with %.17g in '" << line << "'");
  }
  BOOST_TEST(line == fields[0] + " " + fields[1] + " " + fields[2] + " " + fields[3]);
  return {v[0], Eigen::Vector3d(v[1], v[2], v[3])};
}

std::vector<Answer> parseAnswers(const std::string& out) {
  std::vector<Answer> answers;
  for (const auto& line : lines(out)) answers.push_back(parseAnswer(line));
  return answers;
}

/// Checks the last stderr line "queries N total_us T".
void checkSummary(const std::string& err, std::size_t queries) {
  const std::vector<std::string> l = lines(err);
  BOOST_TEST_REQUIRE(!l.empty());
  std::smatch m;
  BOOST_TEST_REQUIRE(std::regex_match(l.back(), m, std::regex("queries ([0-9]+) total_us ([0-9]+)")),
                     "stderr last line '" << l.back() << "'");
  BOOST_TEST(std::stoul(m[1].str()) == queries);
}

/// A shape as given to the tool, and built in-process from the same points.
struct Shape {
  std::string id;
  std::vector<Eigen::Vector3d> points;
};

/// A query as given to the tool: the printed pose values, parsed back exactly.
struct Query {
  int a = 0;
  int b = 0;
  double pa[7];
  double pb[7];
};

/// The pose the tool builds from "tx ty tz qw qx qy qz" (the quaternion divided by its norm).
Eigen::Isometry3d poseOf(const double* p) {
  Eigen::Quaterniond q(p[3], p[4], p[5], p[6]);
  q.coeffs() /= q.norm();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return X;
}

void setPose(double* p, const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  const double v[7] = {t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()};
  for (int i = 0; i < 7; ++i) p[i] = std::strtod(fmt(v[i]).c_str(), nullptr);
}

std::string inputText(const std::vector<Shape>& shapes, const std::vector<Query>& queries) {
  std::string s = "# generated by test_tool\n";
  for (const auto& shape : shapes) {
    s += "shape " + shape.id + " " + std::to_string(shape.points.size()) + "\n";
    for (const auto& p : shape.points) s += fmt(p.x()) + " " + fmt(p.y()) + " " + fmt(p.z()) + "\n";
  }
  s += "\n";
  for (const auto& q : queries) {
    s += "query " + shapes[q.a].id;
    for (double v : q.pa) s += " " + fmt(v);
    s += " " + shapes[q.b].id;
    for (double v : q.pb) s += " " + fmt(v);
    s += "\n";
  }
  return s;
}

Eigen::Vector3d randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}

Eigen::Quaterniond randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
}

/// Shapes of several kinds and runs of 3 consecutive queries per pair (small motions between
/// them, as a planner makes), overlapping and apart.
struct Scenario {
  std::vector<Shape> shapes;
  std::vector<ConvexPolytope> hulls;
  std::vector<Query> queries;
};

Scenario makeScenario(unsigned seed, int runs,
                      const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
  std::mt19937 rng(seed);
  Scenario s;
  s.shapes.push_back({"box", {}});
  for (int i = 0; i < 8; ++i) {
    s.shapes.back().points.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 1.0 / 3.0 : -1.0 / 3.0,
                                        (i & 4) ? 0.3 : -0.3);
  }
  s.shapes.push_back({"tetra", {{0.4, 0.4, 0.4}, {0.4, -0.4, -0.4}, {-0.4, 0.4, -0.4}, {-0.4, -0.4, 0.4}}});
  for (const auto& [id, n, semi] :
       {std::tuple{"blob", 40, Eigen::Vector3d(0.6, 0.45, 0.3)},
        std::tuple{"rod", 30, Eigen::Vector3d(0.15, 0.2, 0.9)},
        std::tuple{"pebble", 12, Eigen::Vector3d(0.3, 0.3, 0.25)}}) {
    Shape shape{id, {}};
    for (int i = 0; i < n; ++i) shape.points.push_back(randomUnit(rng).cwiseProduct(semi));
    s.shapes.push_back(shape);
  }
  for (const auto& shape : s.shapes) s.hulls.push_back(ConvexPolytope::fromPoints(shape.points, shape.id));

  std::uniform_int_distribution<int> pick(0, static_cast<int>(s.shapes.size()) - 1);
  std::uniform_real_distribution<double> off(-0.9, 0.9);
  std::uniform_real_distribution<double> small(-0.02, 0.02);
  for (int r = 0; r < runs; ++r) {
    const int a = pick(rng);
    const int b = pick(rng);
    Eigen::Vector3d tA = origin + 3.0 * Eigen::Vector3d(off(rng), off(rng), off(rng));
    Eigen::Vector3d tB = tA + Eigen::Vector3d(off(rng), off(rng), off(rng));
    Eigen::Quaterniond qA = randomRotation(rng);
    Eigen::Quaterniond qB = randomRotation(rng);
    for (int k = 0; k < 3; ++k) {
      Query q;
      q.a = a;
      q.b = b;
      setPose(q.pa, tA, qA);
      setPose(q.pb, tB, qB);
      s.queries.push_back(q);
      tB += Eigen::Vector3d(small(rng), small(rng), small(rng));
      qB = (qB * Eigen::Quaterniond(Eigen::AngleAxisd(small(rng), randomUnit(rng)))).normalized();
    }
  }
  return s;
}

double pairScale(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                 const Eigen::Isometry3d& X_WB) {
  return std::max(A.lengthScale(), B.lengthScale()) + (X_WB * B.center() - X_WA * A.center()).norm();
}

void checkError(const std::string& input, int line, const std::string& mention) {
  const Run r = runTool("pd", input);
  BOOST_TEST(r.status == 1, "exit status for input:\n" << input);
  BOOST_TEST(r.out.empty(), "no answers on stdout for a bad input");
  BOOST_TEST(r.err.find("line " + std::to_string(line) + ":") != std::string::npos,
             "message '" << r.err << "' names line " << line);
  BOOST_TEST(r.err.find(mention) != std::string::npos,
             "message '" << r.err << "' mentions '" << mention << "'");
  BOOST_TEST(lines(r.err).size() == 1u, "one error line: '" << r.err << "'");
}

const char* const kTwoPoints = "shape a 2\n0 0 0\n1 0 0\n";

/// Runs the tool on a scenario and compares every answer with the exact reference.
void checkAgainstExact(const Scenario& s, const std::string& args) {
  const Run r = runTool(args, inputText(s.shapes, s.queries));
  BOOST_TEST_REQUIRE(r.status == 0, "stderr: " << r.err);
  checkSummary(r.err, s.queries.size());
  const std::vector<Answer> answers = parseAnswers(r.out);
  BOOST_TEST_REQUIRE(answers.size() == s.queries.size());
  int overlapping = 0;
  for (std::size_t i = 0; i < answers.size(); ++i) {
    const Query& q = s.queries[i];
    const Eigen::Isometry3d X_WA = poseOf(q.pa);
    const Eigen::Isometry3d X_WB = poseOf(q.pb);
    const ExactResult e = exactSignedDistance(s.hulls[q.a], X_WA, s.hulls[q.b], X_WB);
    const double L = pairScale(s.hulls[q.a], X_WA, s.hulls[q.b], X_WB);
    overlapping += e.distance < 0.0 ? 1 : 0;
    BOOST_TEST(std::abs(answers[i].sd - e.distance) <= kAgree * L,
               args << " query " << i << ": tool " << answers[i].sd << ", exact " << e.distance);
    BOOST_TEST(std::abs(answers[i].n.norm() - 1.0) <= kNormalAgree);
    if (std::abs(e.distance) > kNormalAgree * L) {
      BOOST_TEST((answers[i].n - e.normal).norm() <= kNormalAgree,
                 args << " query " << i << ": normal " << answers[i].n.transpose() << ", exact "
                      << e.normal.transpose());
    }
  }
  // Both outcomes are represented.
  BOOST_TEST(overlapping > static_cast<int>(answers.size()) / 5);
  BOOST_TEST(overlapping < static_cast<int>(answers.size()) * 4 / 5);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_pd)

BOOST_AUTO_TEST_CASE(answers_match_exact_reference) {
  const Scenario s = makeScenario(4242, 150);
  checkAgainstExact(s, "pd");
  checkAgainstExact(s, "pd --cold");
}

BOOST_AUTO_TEST_CASE(far_from_origin_answers_match_exact_reference) {
  checkAgainstExact(makeScenario(8080, 40, Eigen::Vector3d(1e4, -1e4, 1e4)), "pd");
}

BOOST_AUTO_TEST_CASE(exact_flag_equals_in_process_exact) {
  const Scenario s = makeScenario(77, 10);
  const Run r = runTool("pd --exact", inputText(s.shapes, s.queries));
  BOOST_TEST_REQUIRE(r.status == 0, "stderr: " << r.err);
  checkSummary(r.err, s.queries.size());
  const std::vector<Answer> answers = parseAnswers(r.out);
  BOOST_TEST_REQUIRE(answers.size() == s.queries.size());
  for (std::size_t i = 0; i < answers.size(); ++i) {
    const Query& q = s.queries[i];
    const ExactResult e = exactSignedDistance(s.hulls[q.a], poseOf(q.pa), s.hulls[q.b], poseOf(q.pb));
    // Same code on the same doubles, printed with %.17g: identical.
    BOOST_TEST(answers[i].sd == e.distance);
    BOOST_TEST(answers[i].n.x() == e.normal.x());
    BOOST_TEST(answers[i].n.y() == e.normal.y());
    BOOST_TEST(answers[i].n.z() == e.normal.z());
  }
}

BOOST_AUTO_TEST_CASE(cold_equals_warm) {
  const Scenario s = makeScenario(1001, 100);
  const std::string input = inputText(s.shapes, s.queries);
  const Run warm = runTool("pd", input);
  const Run cold = runTool("pd --cold", input);
  BOOST_TEST_REQUIRE(warm.status == 0, "stderr: " << warm.err);
  BOOST_TEST_REQUIRE(cold.status == 0, "stderr: " << cold.err);
  checkSummary(cold.err, s.queries.size());
  const std::vector<Answer> a = parseAnswers(warm.out);
  const std::vector<Answer> b = parseAnswers(cold.out);
  BOOST_TEST_REQUIRE(a.size() == s.queries.size());
  BOOST_TEST_REQUIRE(b.size() == s.queries.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    BOOST_TEST(std::abs(a[i].sd - b[i].sd) <= kColdWarm,
               "query " << i << ": warm " << a[i].sd << ", cold " << b[i].sd);
    BOOST_TEST((a[i].n - b[i].n).norm() <= kColdWarm,
               "query " << i << ": warm " << a[i].n.transpose() << ", cold " << b[i].n.transpose());
  }
}

BOOST_AUTO_TEST_CASE(example_file_runs) {
  const std::string example = readFile(fs::path(DEEPCHECK_SOURCE_DIR) / "tools/examples/pd_boxes.txt");
  BOOST_TEST_REQUIRE(!example.empty());
  const Run r = runTool("pd", example);
  BOOST_TEST_REQUIRE(r.status == 0, "stderr: " << r.err);
  const std::vector<Answer> answers = parseAnswers(r.out);
  BOOST_TEST_REQUIRE(answers.size() == 7u);
  checkSummary(r.err, 7);
  // Apart along x by 0.7 (the first query, as the example's comment says).
  BOOST_TEST(std::abs(answers[0].sd - 0.7) <= kAgree);
  BOOST_TEST((answers[0].n - Eigen::Vector3d::UnitX()).norm() <= kAgree);
  // The slab at x = 0.7 reaches x = 0.4, 0.1 into the cube: the least overlap of the three axes.
  BOOST_TEST(std::abs(answers[2].sd + 0.1) <= kAgree);
  // Near and far from the world origin: the same answer up to the input's rounding.
  BOOST_TEST(std::abs(answers[4].sd - answers[5].sd) <= kAgree);
  BOOST_TEST(answers[4].sd < 0.0);
  BOOST_TEST(answers[6].sd > 0.0);
}

BOOST_AUTO_TEST_CASE(comments_blank_lines_and_crlf) {
  const std::string input =
      "# header\r\n\r\n   \nshape p 1\r\n# a comment between points\n0 0 0\r\n  # indented comment\n"
      "shape q 1\n1 2 2\nquery p 0 0 0 1 0 0 0 q 0 0 0 1 0 0 0\r\n";
  const Run r = runTool("pd", input);
  BOOST_TEST_REQUIRE(r.status == 0, "stderr: " << r.err);
  const std::vector<Answer> answers = parseAnswers(r.out);
  BOOST_TEST_REQUIRE(answers.size() == 1u);
  BOOST_TEST(std::abs(answers[0].sd - 3.0) <= kAgree);
  BOOST_TEST((answers[0].n - Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0).norm() <= kAgree);
}

BOOST_AUTO_TEST_CASE(empty_input_gives_zero_queries) {
  const Run r = runTool("pd", "# nothing\n");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.empty());
  BOOST_TEST(lines(r.err).back() == "queries 0 total_us 0");
}

BOOST_AUTO_TEST_CASE(bad_inputs_are_reported_with_line_numbers) {
  const std::string q = " 0 0 0 1 0 0 0 ";
  checkError(std::string(kTwoPoints) + "query a 0 0 0 1.01 0 0 0 a 0 0 0 1 0 0 0\n", 4,
             "quaternion of A (shape 'a') has norm 1.01");
  checkError(std::string(kTwoPoints) + "query a" + q + "a 0 0 0 0.5 0.5 0.5 0.500003\n", 4,
             "quaternion of B");
  checkError(std::string(kTwoPoints) + "\nquery a" + q + "b" + q + "\n", 5, "unknown shape id 'b'");
  checkError(std::string(kTwoPoints) + "query c" + q + "a" + q + "\n", 4, "unknown shape id 'c'");
  checkError(std::string(kTwoPoints) + "# again\nshape a 1\n0 0 0\n", 5,
             "duplicate shape id 'a' (first defined on line 1)");
  checkError("shape a 2\n0 0 0\n1 nan 0\n", 3, "'nan' is not a finite number");
  checkError("shape a 2\n0 0 0\n1 inf 0\n", 3, "'inf' is not a finite number");
  checkError(std::string(kTwoPoints) + "query a 0 0 0 1 0 0 NaN a" + q + "\n", 4, "'NaN'");
  checkError("shape a 2\n0 0 0\n1 0x 0\n", 3, "'0x' is not a number");
  checkError("shape a 3\n0 0 0\n1 0 0\nquery a" + q + "a" + q + "\n", 4,
             "declares 3 points but only 2 precede this line");
  checkError("shape a 3\n0 0 0\n1 0 0\n", 1, "declares 3 points but the input ends after 2");
  checkError("shape a 2\n0 0 0\n1 0 0 0\n", 3, "expected a point");
  checkError("shape a 2\n0 0 0\n1 0\n", 3, "expected a point");
  checkError("shape a 0\n", 1, "not a positive integer");
  checkError("shape a two\n", 1, "not a positive integer");
  checkError("shape a\n", 1, "expected 'shape <id> <n>'");
  checkError(std::string(kTwoPoints) + "query a 0 0 0 1 0 0 a" + q + "\n", 4, "17 fields, got 16");
  checkError("shap a 1\n0 0 0\n", 1, "unknown keyword 'shap'");
  checkError("0 0 0\n", 1, "unknown keyword '0'");
}

BOOST_AUTO_TEST_CASE(accepted_quaternions_within_tolerance) {
  // A quaternion printed with 8 digits (norm 1 within 1e-6) is accepted.
  const Run r = runTool("pd", std::string(kTwoPoints) +
                                  "query a 0 0 0 0.70710678 0 0 0.70710678 a 0 3 0 1 0 0 0\n");
  BOOST_TEST_REQUIRE(r.status == 0, "stderr: " << r.err);
  const std::vector<Answer> answers = parseAnswers(r.out);
  BOOST_TEST_REQUIRE(answers.size() == 1u);
  // A's segment is turned onto the y axis: it reaches y = 1, B's segment lies at y = 3.
  BOOST_TEST(std::abs(answers[0].sd - 2.0) <= kNormalAgree);
}

BOOST_AUTO_TEST_CASE(command_line_errors) {
  Run r = runTool("pd --bogus", "");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("unknown option '--bogus'") != std::string::npos);
  BOOST_TEST(r.err.find("usage: deepcheck pd") != std::string::npos);

  r = runTool("pd extra.txt", "");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("unexpected argument 'extra.txt'") != std::string::npos);

  r = runTool("frobnicate", "");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.out.empty());
  BOOST_TEST(r.err.find("unknown subcommand 'frobnicate'") != std::string::npos);
  BOOST_TEST(r.err.find("usage: deepcheck") != std::string::npos);

  r = runTool("", "");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("usage: deepcheck") != std::string::npos);

  r = runTool("--help", "");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("pd") != std::string::npos);

  r = runTool("pd --help", "");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("usage: deepcheck pd [--cold] [--exact]") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
