// view_bench: how large the viewer's page (viewer/html_view.h) gets, and how long writing it
// takes, for a robot of 20 revolute joints whose links carry 500 convex pieces in all, along a
// path of 1,000 waypoints (frames = waypoints, no densifying). The browser's load time of the
// page is measured by bench/run_view_bench.sh, which runs this program first.
//
//   view_bench OUT.html
// Prints one table row: variables, pieces, frames, page bytes, seconds to build the view (with a
// signed-distance query per frame) and to write it.

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/viewer/html_view.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr int kJoints = 20;
constexpr int kPiecesPerLink = 25;  // 20 moving links x 25 = 500 pieces
constexpr int kWaypoints = 1000;
constexpr double kLinkLength = 0.12;  // metres

/// A serial chain: base + 20 links, joints alternating about z and y, each moving link wrapped by
/// 25 small cylinders (circumscribed prisms: 16 to 20 vertices each) around its axis.
std::string chainUrdf() {
  std::ostringstream u;
  u << "<robot name=\"bench_chain\">\n<link name=\"base\"/>\n";
  for (int j = 0; j < kJoints; ++j) {
    u << "<link name=\"l" << j << "\">\n";
    for (int k = 0; k < kPiecesPerLink; ++k) {
      const double angle = 2.0 * M_PI * (k % 5) / 5.0;
      const double z = kLinkLength * (0.1 + 0.8 * (k / 5) / 4.0);
      u << "  <collision><origin xyz=\"" << 0.03 * std::cos(angle) << " " << 0.03 * std::sin(angle) << " " << z
        << "\"/><geometry><cylinder radius=\"0.012\" length=\"0.02\"/></geometry></collision>\n";
    }
    u << "</link>\n<joint name=\"j" << j << "\" type=\"revolute\"><parent link=\""
      << (j ? "l" + std::to_string(j - 1) : "base") << "\"/><child link=\"l" << j << "\"/><origin xyz=\"0 0 "
      << (j ? kLinkLength : 0.0) << "\"/><axis xyz=\"" << (j % 2 ? "0 1 0" : "0 0 1")
      << "\"/><limit lower=\"-2.5\" upper=\"2.5\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  u << "</robot>\n";
  return u.str();
}

/// A smooth path: every joint a sinusoid of its own frequency, within +-0.6 rad.
std::vector<Eigen::VectorXd> wavePath() {
  std::vector<Eigen::VectorXd> path;
  for (int i = 0; i < kWaypoints; ++i) {
    Eigen::VectorXd q(kJoints);
    for (int j = 0; j < kJoints; ++j) q[j] = 0.6 * std::sin(2.0 * M_PI * (1.0 + 0.13 * j) * i / kWaypoints);
    path.push_back(q);
  }
  return path;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: view_bench OUT.html\n");
    return 2;
  }
  try {
    const deepcheck::checker::World world(deepcheck::robots::RobotModel::fromUrdfString(chainUrdf(), "."));
    const std::vector<Eigen::VectorXd> path = wavePath();
    deepcheck::viewer::WorldViewOptions options;
    options.title = "view_bench: 20 joints, 500 pieces, 1,000 waypoints";
    options.maxStep = 0.0;
    auto start = std::chrono::steady_clock::now();
    const deepcheck::viewer::ViewScene scene = deepcheck::viewer::viewOfWorld(world, path, options);
    const double build = secondsSince(start);
    start = std::chrono::steady_clock::now();
    deepcheck::viewer::writeHtmlView(scene, std::string(argv[1]));
    const double write = secondsSince(start);
    std::printf("%-9s %-6s %-6s %-11s %-9s %-9s\n", "variables", "pieces", "frames", "page_bytes", "build_s",
                "write_s");
    std::printf("%-9d %-6d %-6zu %-11ju %-9.3f %-9.3f\n", world.robot().numVariables(),
                world.summaryCounts().robotPieces, scene.frames.size(),
                static_cast<std::uintmax_t>(std::filesystem::file_size(argv[1])), build, write);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "view_bench: %s\n", e.what());
    return 1;
  }
}
