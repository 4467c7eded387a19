#pragma once
// Helpers shared by the robots test files: where ../shared is, temporary folders, and checks of
// exception messages.

#include "common/test_paths.h"

#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace deepcheck::robots::test {

using deepcheck::test::haveShared;
using deepcheck::test::sharedDir;

/// A fresh folder under the system temporary directory, removed with everything in it on
/// destruction. Names are unique per process and per instance.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
            ("deepcheck_robots_test_" + std::to_string(::getpid()) + "_" +
             std::to_string(counter++) + "_" + std::to_string(stamp));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Writes `content` to `relative` (folders created) and returns the full path.
  std::string write(const std::string& relative, const std::string& content) const {
    const std::filesystem::path p = path_ / relative;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p.string();
  }

 private:
  std::filesystem::path path_;
};

/// The Panda of the shared data folder (call only when haveShared()).
inline RobotModel loadPanda() {
  LoadOptions o;
  o.packageRoots = {sharedDir() + "/robots/panda"};
  o.useRosPackagePath = false;
  return RobotModel::fromUrdfFile(sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf", o);
}

/// The bundled arm (robots/data), ROS_PACKAGE_PATH ignored.
inline RobotModel loadBundledArm() {
  LoadOptions o;
  o.packageRoots = {deepcheck::test::bundledDataDir()};
  o.useRosPackagePath = false;
  return RobotModel::fromUrdfFile(deepcheck::test::bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf", o);
}

/// Runs f, which must throw std::invalid_argument whose message contains every one of `parts`.
inline void checkThrows(const std::function<void()>& f, std::initializer_list<std::string> parts) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    BOOST_TEST_MESSAGE("message: " << message);
    for (const std::string& part : parts) {
      BOOST_CHECK_MESSAGE(message.find(part) != std::string::npos,
                          "message lacks '" << part << "': " << message);
    }
    return;
  } catch (const std::exception& e) {
    BOOST_ERROR("expected std::invalid_argument, got another exception: " << e.what());
    return;
  }
  BOOST_ERROR("expected std::invalid_argument, nothing was thrown");
}

}  // namespace deepcheck::robots::test
