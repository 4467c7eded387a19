#pragma once
// Where the test suites find their data: the shared data folder (../shared beside the source
// tree: real robots and scenes) and the project's own data (robots/data). Every suite gets
// DEEPCHECK_SHARED_DIR and DEEPCHECK_SOURCE_DIR from tests/CMakeLists.txt; tests that need
// ../shared skip with a message when it is absent.

#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <string>
#include <system_error>

namespace deepcheck::test {

/// The shared data folder (../shared of the source tree), or "" when it is absent.
inline std::string sharedDir() {
#ifdef DEEPCHECK_SHARED_DIR
  std::error_code ec;
  if (std::filesystem::is_directory(std::filesystem::path(DEEPCHECK_SHARED_DIR) / "robots", ec)) {
    return DEEPCHECK_SHARED_DIR;
  }
#endif
  return "";
}

/// True when ../shared is present; otherwise logs why the calling test is skipped.
inline bool haveShared(const char* what) {
  if (!sharedDir().empty()) return true;
  BOOST_TEST_MESSAGE("skipped " << what
                                << ": the shared data folder (../shared beside the source tree, with "
                                   "robots/ and scenes/) is absent");
  return false;
}

/// The project's own data (robots/data): the bundled arm, its SRDF and the scenes.
inline std::string bundledDataDir() {
#ifdef DEEPCHECK_SOURCE_DIR
  return std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
#else
  return "robots/data";
#endif
}

}  // namespace deepcheck::test
