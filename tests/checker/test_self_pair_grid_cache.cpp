// On-disk cache of the self-pair grids (checker/src/self_pair_grid_cache.h): a miss stores, a hit
// reads the same flags, a corrupt or forged entry is rebuilt (with a note), another tolerance or
// joint limit is another key, an unwritable directory only leaves the grids uncached, and a world
// built through a warm cache answers isFree as one without grids.

#include "checker_test_util.h"
#include "common/read_text.h"

#include "self_pair_grid.h"
#include "self_pair_grid_cache.h"
#include "world_test_access.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/decomposition/cache_file.h"
#include "deepcheck/robots/pair_filter.h"

#include <boost/test/unit_test.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;
using deepcheck::test::readText;
using detail::SelfPairGrid;
using detail::SelfPairGridCache;

namespace fs = std::filesystem;

namespace {

std::string armUrdf() { return bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf"; }

robots::RobotModel armWithUrdfText(const std::string& text) {
  return robots::RobotModel::fromUrdfString(text, fs::path(armUrdf()).parent_path().string(), bundledLoadOptions(),
                                            "deepcheck_arm.urdf");
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

/// An empty directory for one test case, in the build folder.
std::string freshDir(const std::string& name) {
  const fs::path dir = fs::path(testCacheDir()).parent_path() / "grid_cache_tests" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

/// The grid-*.bin files of `dir`.
std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().rfind("grid-", 0) == 0) files.push_back(e.path().string());
  }
  return files;
}

std::vector<bool> flags(const SelfPairGrid& grid) {
  std::vector<bool> out;
  for (int i = 0; i < grid.numCells(); ++i) out.push_back(grid.cellFree(i));
  return out;
}

/// A world of the arm (through the tests' decomposition cache) and its first pair with a grid.
struct ArmGrid {
  explicit ArmGrid(robots::RobotModel model = robots::RobotModel::fromUrdfFile(armUrdf(), bundledLoadOptions()))
      : world(std::move(model), armOptions()) {
    robot = robotOf(world);
    for (const detail::SelfPair& p : selfPairsOf(world)) {
      if (p.grid && a < 0) {
        a = p.a;
        b = p.b;
      }
    }
    BOOST_REQUIRE(a >= 0);
    truth = SelfPairGrid::build(*robot, a, b);  // no cache
  }
  static WorldOptions armOptions() {
    WorldOptions o = testWorldOptions();
    o.disabledPairs = robots::readSrdfDisabledPairs(bundledDataDir() + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
    return o;
  }
  /// The pair's grid through `cache`; what it noted in `*notes`.
  std::shared_ptr<const SelfPairGrid> build(const SelfPairGridCache& cache, std::string* notes) const {
    std::ostringstream out;
    auto grid = SelfPairGrid::build(*robot, a, b, &cache, &out);
    *notes = out.str();
    return grid;
  }
  World world;
  std::shared_ptr<const detail::RobotData> robot;
  int a = -1;
  int b = -1;
  std::shared_ptr<const SelfPairGrid> truth;
};

/// The arm's ArmGrid, made once for the cases that read it only (a world and a grid without cache
/// take seconds under the sanitizers).
const ArmGrid& sharedArm() {
  static const ArmGrid arm;
  return arm;
}

ino_t inodeOf(const std::string& path) {
  struct stat s {};
  BOOST_REQUIRE(::stat(path.c_str(), &s) == 0);
  return s.st_ino;
}

/// Rewrites the entry at `path` with its cell flags changed by `edit` and a valid checksum.
void forge(const std::string& path, const std::function<void(std::string& cells)>& edit) {
  std::string data = readText(path);
  const std::size_t header = 8 + 4 + 16 + 4;
  std::string cells = data.substr(header, data.size() - header - 8);
  edit(cells);
  std::string body = data.substr(0, header) + cells;
  const std::uint64_t sum = decomposition::fnv1a(body.data(), body.size());
  for (int i = 0; i < 8; ++i) body.push_back(static_cast<char>(sum >> (8 * i)));
  writeText(path, body);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_self_pair_grid_cache)

BOOST_AUTO_TEST_CASE(miss_stores_and_hit_reads_the_same_flags) {
  const ArmGrid& arm = sharedArm();
  const SelfPairGridCache cache(freshDir("hit_miss"));
  std::string notes;
  auto first = arm.build(cache, &notes);
  BOOST_TEST(notes == "");
  const std::vector<std::string> stored = entries(cache.directory());
  BOOST_REQUIRE(stored.size() == 1u);
  const ino_t inode = inodeOf(stored[0]);
  auto second = arm.build(cache, &notes);
  BOOST_TEST(notes == "");
  BOOST_TEST(inodeOf(stored[0]) == inode);  // a hit does not write the entry again
  BOOST_TEST(entries(cache.directory()).size() == 1u);
  BOOST_TEST((flags(*first) == flags(*arm.truth)));
  BOOST_TEST((flags(*second) == flags(*arm.truth)));
  BOOST_TEST(second->motionBound() == arm.truth->motionBound());
  BOOST_TEST(arm.truth->numFreeCells() > 0);
}

BOOST_AUTO_TEST_CASE(warm_world_answers_as_one_without_grids) {
  WorldOptions options = ArmGrid::armOptions();
  const auto model = [] { return robots::RobotModel::fromUrdfFile(armUrdf(), bundledLoadOptions()); };
  { World cold(model(), options); }  // stores the grids beside the decomposition cache
  World warm(model(), options);
  World without(model(), options);
  disableSelfPairGrids(without);
  BOOST_TEST(warm.summary().find("certified-free grid") != std::string::npos);
  std::mt19937 rng(29);
  const std::vector<Eigen::VectorXd> qs = randomConfigurations(warm.robot(), 4000, rng);
  QueryStats stats;
  const int colliding = compareIsFree(warm, without, qs, "the cached grids", &stats);
  BOOST_TEST(colliding > 0);
  BOOST_TEST(colliding < static_cast<int>(qs.size()));
  BOOST_TEST(stats.certifiedSelf > 0u);
}

BOOST_AUTO_TEST_CASE(corrupt_entry_is_rebuilt_with_one_note) {
  const ArmGrid& arm = sharedArm();
  const SelfPairGridCache cache(freshDir("corrupt"));
  std::string notes;
  arm.build(cache, &notes);
  const std::string path = entries(cache.directory()).at(0);
  std::string data = readText(path);
  data[data.size() / 2] ^= 0x5a;
  writeText(path, data);
  auto rebuilt = arm.build(cache, &notes);
  BOOST_TEST(notes.find("checksum mismatch") != std::string::npos, notes);
  BOOST_TEST(std::count(notes.begin(), notes.end(), '\n') == 1);
  BOOST_TEST((flags(*rebuilt) == flags(*arm.truth)));
  arm.build(cache, &notes);  // replaced by a good entry
  BOOST_TEST(notes == "");
  writeText(path, data.substr(0, 20));
  BOOST_TEST((flags(*arm.build(cache, &notes)) == flags(*arm.truth)));
  BOOST_TEST(notes.find("truncated") != std::string::npos, notes);
}

BOOST_AUTO_TEST_CASE(another_version_is_rebuilt_silently) {
  const ArmGrid& arm = sharedArm();
  const SelfPairGridCache cache(freshDir("version"));
  std::string notes;
  arm.build(cache, &notes);
  const std::string path = entries(cache.directory()).at(0);
  std::string data = readText(path);
  data[8] = static_cast<char>(detail::kGridCacheFormatVersion + 1);
  data.resize(data.size() - 8);
  const std::uint64_t sum = decomposition::fnv1a(data.data(), data.size());
  for (int i = 0; i < 8; ++i) data.push_back(static_cast<char>(sum >> (8 * i)));
  writeText(path, data);
  BOOST_TEST((flags(*arm.build(cache, &notes)) == flags(*arm.truth)));
  BOOST_TEST(notes == "");
  BOOST_TEST(readText(path) != data);  // replaced
}

BOOST_AUTO_TEST_CASE(another_tolerance_or_limit_is_another_key) {
  const ArmGrid& arm = sharedArm();
  const robots::RobotModel& m = arm.robot->model;
  auto isAncestor = [&](int ancestor, int link) {
    for (int l = link; l >= 0; l = m.link(l).parentLink) {
      if (l == ancestor) return true;
    }
    return false;
  };
  int ga = arm.a;
  int gb = arm.b;
  if (!isAncestor(arm.robot->links[ga].link, arm.robot->links[gb].link)) std::swap(ga, gb);
  const detail::LinkGeometry& U = arm.robot->links[ga];
  const detail::LinkGeometry& D = arm.robot->links[gb];
  const int up = U.link;
  const int down = D.link;
  const std::vector<double> layout = {2.0, 0.01, 5.0, -1.0, 0.1, 10.0, 20.0, 6.0, -2.0, 0.2, 5.0, 20.0};
  const std::vector<double> tolerances = detail::gridCertificateTolerances();
  const std::string key = detail::selfPairGridKey(*arm.robot, up, down, U, D, layout, tolerances);
  BOOST_TEST(key.size() == 32u);
  BOOST_TEST(detail::selfPairGridKey(*arm.robot, up, down, U, D, layout, tolerances) == key);
  for (std::size_t k = 0; k < tolerances.size(); ++k) {
    std::vector<double> other = tolerances;
    other[k] *= 1.0 + 1.0 / 3.0;
    BOOST_TEST(detail::selfPairGridKey(*arm.robot, up, down, U, D, layout, other) != key, "tolerance " << k);
  }
  for (std::size_t k = 0; k < layout.size(); ++k) {
    std::vector<double> other = layout;
    other[k] += 1.0 / 3.0;
    BOOST_TEST(detail::selfPairGridKey(*arm.robot, up, down, U, D, other, tolerances) != key, "layout " << k);
  }
  // Another limit of joint7: another entry beside the first, built without a note.
  const SelfPairGridCache cache(freshDir("limit"));
  std::string notes;
  arm.build(cache, &notes);
  std::string text = readText(armUrdf());
  const std::string limit = "lower=\"-3.05433\" upper=\"3.05433\"";
  BOOST_REQUIRE(text.find(limit) != std::string::npos);
  text.replace(text.find(limit), limit.size(), "lower=\"-3.05433\" upper=\"3.0\"");
  const ArmGrid changed(armWithUrdfText(text));
  changed.build(cache, &notes);
  BOOST_TEST(notes == "");
  BOOST_TEST(entries(cache.directory()).size() == 2u);
}

BOOST_AUTO_TEST_CASE(forged_entry_marking_colliding_cells_free_is_rejected) {
  const ArmGrid& arm = sharedArm();
  const SelfPairGridCache cache(freshDir("forged"));
  std::string notes;
  arm.build(cache, &notes);
  const std::string path = entries(cache.directory()).at(0);
  // The grid has cells not certified free (pieces near or in contact): a forged entry says FREE.
  BOOST_REQUIRE(arm.truth->numFreeCells() < arm.truth->numCells());
  forge(path, [](std::string& cells) { std::fill(cells.begin(), cells.end(), '\1'); });
  auto rebuilt = arm.build(cache, &notes);
  BOOST_TEST(notes.find("fails its certificate") != std::string::npos, notes);
  BOOST_TEST((flags(*rebuilt) == flags(*arm.truth)));
  arm.build(cache, &notes);
  BOOST_TEST(notes == "");  // replaced by the true flags
}

BOOST_AUTO_TEST_CASE(unwritable_or_disabled_directory_leaves_the_grid_uncached) {
  const ArmGrid& arm = sharedArm();
  const std::string dir = freshDir("unwritable");
  writeText(dir + "/file", "not a directory");
  std::string notes;
  for (const SelfPairGridCache& cache : {SelfPairGridCache(dir + "/file/sub"), SelfPairGridCache("")}) {
    BOOST_TEST((flags(*arm.build(cache, &notes)) == flags(*arm.truth)));
    BOOST_TEST(notes == "");
  }
  BOOST_TEST(entries(dir).empty());
  BOOST_TEST(!SelfPairGridCache("").enabled());
}

BOOST_AUTO_TEST_SUITE_END()
