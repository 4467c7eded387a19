// load_bench: how loading grows with the size of what is loaded. For each size N it times, on
// the bundled arm (its SRDF's disabled pairs), from text in memory to a World ready to query:
//   scene_yaml     a MoveIt planning scene of N boxes (parsePlanningScene + addPlanningScene)
//   obstacles      N boxes added one by one with World::addObstacle (each a change of the world)
//   obstacles_batch  the same boxes added together with World::addObstacles
//   scene_urdf     a scene URDF of N box links (fromUrdfString + addScene)
//   robot_star     a robot URDF of N box links on revolute joints, all children of a box base
//                  (fromUrdfString + the World's construction: pieces, self pairs, grids)
//   robot_hub      the same around a base without geometry (every two children adjacent)
//   mesh           a closed mesh of about N triangles (a tessellated sphere, one convex piece)
//                  added as an obstacle: the mesh's cleaning, hull and decomposition
//   hand           a non-convex mesh of about N triangles (hand_mesh.h: a palm and four curled
//                  fingers) decomposed by decomposeConvex with the default parameters, as a
//                  world's first load does; also its pieces and excess (the report's concavity:
//                  how far the pieces stick out of the mesh, metres)
//   comb           the same with eight thinner fingers (hand_mesh.h), about 50 pieces
// Usage: load_bench [--sizes 250,500,...] [--kinds scene_yaml,...] [--out folder]
// Prints a table and writes <out>/load_bench.csv (kind, n, seconds, µs per item, and for `hand`
// pieces and excess in metres).
// bench/run_load_bench.sh runs it and plots the curves.

#include "format.h"
#include "hand_mesh.h"
#include "options.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/srdf.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace dc = deepcheck::checker;
namespace dd = deepcheck::decomposition;
namespace dr = deepcheck::robots;

namespace {

const std::string kData = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";

/// The bundled arm with its SRDF's disabled pairs; meshes decomposed through the cache in
/// `cacheDir` ("" the default).
dc::World bundledArm(const std::string& cacheDir = "") {
  dr::LoadOptions load;
  load.packageRoots = {kData};
  dc::WorldOptions options;
  options.decompositionCacheDir = cacheDir;
  options.disabledPairs = dr::readSrdfDisabledPairs(kData + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
  return dc::World(dr::RobotModel::fromUrdfFile(kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf", load), options);
}

/// Box i of N on a grid beside the arm: 2 cm boxes 5 cm apart, in a slab of rows.
Eigen::Vector3d gridPosition(int i) {
  return Eigen::Vector3d(1.0 + 0.05 * (i % 40), -1.0 + 0.05 * ((i / 40) % 40), 0.05 * (i / 1600));
}

dc::Obstacle gridBox(int i) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = gridPosition(i);
  return dc::Obstacle::box("box" + std::to_string(i), Eigen::Vector3d::Constant(0.02), X);
}

std::string planningSceneYaml(int n) {
  std::ostringstream y;
  y << "name: grid\nworld:\n  collision_objects:\n";
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = gridPosition(i);
    y << "    - id: box" << i << "\n      header: {frame_id: base_link}\n      pose:\n"
      << "        position: {x: " << p.x() << ", y: " << p.y() << ", z: " << p.z() << "}\n"
      << "        orientation: {x: 0, y: 0, z: 0, w: 1}\n"
      << "      primitives:\n        - type: box\n          dimensions: [0.02, 0.02, 0.02]\n"
      << "      primitive_poses:\n        - position: {x: 0, y: 0, z: 0}\n          orientation: {x: 0, y: 0, z: 0, w: "
         "1}\n";
  }
  return y.str();
}

std::string boxLink(const std::string& name) {
  return "<link name='" + name + "'><collision><geometry><box size='0.02 0.02 0.02'/></geometry></collision></link>";
}

std::string sceneUrdf(int n) {
  std::ostringstream u;
  u << "<robot name='grid'><link name='world'/>";
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = gridPosition(i);
    u << boxLink("b" + std::to_string(i)) << "<joint name='j" << i
      << "' type='fixed'><parent link='world'/><child link='b" << i << "'/><origin xyz='" << p.x() << " " << p.y()
      << " " << p.z() << "'/></joint>";
  }
  u << "</robot>";
  return u.str();
}

/// N box links on revolute joints around a hub: a box (`hubGeometry`) or a link without geometry,
/// which makes every two of its children adjacent.
std::string starUrdf(int n, bool hubGeometry) {
  std::ostringstream u;
  u << "<robot name='star'>" << (hubGeometry ? boxLink("base") : std::string("<link name='base'/>"));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    u << boxLink("l" + std::to_string(i)) << "<joint name='j" << i
      << "' type='revolute'><parent link='base'/><child link='l" << i << "'/><origin xyz='" << std::cos(a) << " "
      << std::sin(a) << " 0'/><axis xyz='0 0 1'/>"
      << "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>";
  }
  u << "</robot>";
  return u.str();
}

/// A sphere of radius 0.1 tessellated into about n triangles (latitude-longitude bands).
dr::TriangleMesh sphereMesh(int n) {
  const int bands = std::max(3, static_cast<int>(std::sqrt(n / 2.0)));
  dr::TriangleMesh m;
  m.vertices.emplace_back(0, 0, 0.1);
  for (int b = 1; b < bands; ++b) {
    const double t = M_PI * b / bands;
    for (int k = 0; k < bands; ++k) {
      const double p = 2 * M_PI * k / bands;
      m.vertices.emplace_back(0.1 * std::sin(t) * std::cos(p), 0.1 * std::sin(t) * std::sin(p), 0.1 * std::cos(t));
    }
  }
  m.vertices.emplace_back(0, 0, -0.1);
  const int south = static_cast<int>(m.vertices.size()) - 1;
  auto ring = [&](int b, int k) { return 1 + (b - 1) * bands + (k % bands); };
  for (int k = 0; k < bands; ++k) m.triangles.push_back({0, ring(1, k), ring(1, k + 1)});
  for (int b = 1; b + 1 < bands; ++b) {
    for (int k = 0; k < bands; ++k) {
      m.triangles.push_back({ring(b, k), ring(b + 1, k), ring(b + 1, k + 1)});
      m.triangles.push_back({ring(b, k), ring(b + 1, k + 1), ring(b, k + 1)});
    }
  }
  for (int k = 0; k < bands; ++k) m.triangles.push_back({south, ring(bands - 1, k + 1), ring(bands - 1, k)});
  return m;
}

double seconds(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// What a run measured besides its time: the decomposition's pieces and excess (`hand`, `comb`).
struct Quality {
  int pieces = 0;
  double excess = std::nan("");
};

/// Time of loading one kind at size n (what is built before the clock starts is not counted).
double timeKind(const std::string& kind, int n, int* items, Quality* quality) {
  *items = n;
  if (kind == "hand" || kind == "comb") {
    const dr::TriangleMesh mesh = kind == "hand" ? deepcheck::bench::handMesh(n) : deepcheck::bench::combMesh(n);
    *items = static_cast<int>(mesh.triangles.size());
    dd::ConvexDecomposition d;
    const double s = seconds([&] { d = dd::decomposeConvex(mesh, dd::DecompositionParams{}); });
    quality->pieces = d.report.numPieces;
    quality->excess = d.report.concavity;
    if (!d.report.warning.empty()) std::fprintf(stderr, "load_bench: %s\n", d.report.warning.c_str());
    return s;
  }
  if (kind == "scene_yaml") {
    const std::string yaml = planningSceneYaml(n);
    dc::World world = bundledArm();
    return seconds([&] { world.addPlanningScene(dr::parsePlanningScene(yaml, ".")); });
  }
  if (kind == "obstacles") {
    dc::World world = bundledArm();
    return seconds([&] {
      for (int i = 0; i < n; ++i) world.addObstacle(gridBox(i));
    });
  }
  if (kind == "obstacles_batch") {
    dc::World world = bundledArm();
    std::vector<dc::Obstacle> boxes;
    for (int i = 0; i < n; ++i) boxes.push_back(gridBox(i));
    return seconds([&] { world.addObstacles(boxes); });
  }
  if (kind == "scene_urdf") {
    const std::string urdf = sceneUrdf(n);
    dc::World world = bundledArm();
    return seconds([&] { world.addScene(dr::RobotModel::fromUrdfString(urdf, ".", {}, "grid.urdf")); });
  }
  if (kind == "robot_star" || kind == "robot_hub") {
    const std::string urdf = starUrdf(n, kind == "robot_star");
    return seconds([&] { dc::World world(dr::RobotModel::fromUrdfString(urdf, ".", {}, "star.urdf")); });
  }
  if (kind == "mesh") {
    dr::TriangleMesh mesh = sphereMesh(n);
    *items = static_cast<int>(mesh.triangles.size());
    // A decomposition cache of its own, empty: the first load is timed, not a cache read.
    const std::filesystem::path cache =
        std::filesystem::temp_directory_path() / ("deepcheck_load_bench_" + std::to_string(::getpid()));
    std::filesystem::remove_all(cache);
    dc::World world = bundledArm(cache.string());
    const double s =
        seconds([&] { world.addObstacle(dc::Obstacle::fromMesh("sphere", mesh, Eigen::Isometry3d::Identity())); });
    std::filesystem::remove_all(cache);
    return s;
  }
  throw std::invalid_argument(
      "unknown kind '" + kind +
      "' (scene_yaml, obstacles, obstacles_batch, scene_urdf, robot_star, robot_hub, mesh, hand, comb)");
}

}  // namespace

void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "load_bench: %s\n", error.c_str());
  std::fprintf(stderr,
               "usage: load_bench [--sizes 250,500,1000,2000,4000] [--kinds "
               "scene_yaml,obstacles,obstacles_batch,scene_urdf,robot_star,robot_hub,mesh,hand,comb]\n"
               "                  [--out folder (default bench/results)]\n");
  std::exit(2);
}

int main(int argc, char** argv) {
  std::vector<int> sizes = {250, 500, 1000, 2000, 4000};
  std::vector<std::string> kinds = {
      "scene_yaml", "obstacles", "obstacles_batch", "scene_urdf", "robot_star", "robot_hub", "mesh", "hand"};
  std::string out = DEEPCHECK_BENCH_RESULTS_DIR;
  deepcheck::bench::readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--sizes") {
      sizes.clear();
      for (const std::string& s : deepcheck::bench::splitList(value())) {
        sizes.push_back(deepcheck::bench::positiveCount(s, arg, usage));
      }
    } else if (arg == "--kinds") {
      kinds = deepcheck::bench::splitList(value());
    } else if (arg == "--out") {
      out = value();
    } else {
      return false;
    }
    return true;
  });

  std::ofstream csv(out + "/load_bench.csv");
  if (!csv) usage("cannot write " + out + "/load_bench.csv");
  csv << "kind,n,seconds,us_per_item,pieces,excess_m\n";
  std::printf("%-12s %8s %10s %12s %7s %10s\n", "kind", "n", "seconds", "us per item", "pieces", "excess m");
  for (const std::string& kind : kinds) {
    for (int n : sizes) {
      int items = n;
      Quality q;
      const double s = timeKind(kind, n, &items, &q);
      std::printf("%-12s %8d %10.3f %12.1f", kind.c_str(), items, s, 1e6 * s / items);
      csv << kind << "," << items << "," << s << "," << 1e6 * s / items << ",";
      if (q.pieces > 0) {
        std::printf(" %7d %10.4f", q.pieces, q.excess);
        csv << q.pieces << "," << q.excess;
      } else {
        csv << ",";
      }
      std::printf("\n");
      std::fflush(stdout);
      csv << "\n";
    }
  }
  return 0;
}
