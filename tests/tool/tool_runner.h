#pragma once
// Running the `deepcheck` binary in the end-to-end tests of tests/tool: a scratch folder per test,
// `deepcheck <subcommand> <args>` with a given stdin, its stdout, stderr and exit status, and the
// small text helpers the tests read the output with.
//
// Every run gets the scratch folder's own decomposition cache (XDG_CACHE_HOME), so the tests never
// write to the user's cache. A scratch folder's cache starts as a copy of one that holds the bundled
// arm's decompositions, filled once per test process: decomposing its meshes takes about 1.4 s,
// reading them back 0.03 s, and most tests load that arm. A test that needs an empty cache asks
// for one (Scratch::Cache::Empty).

#include "common/read_text.h"
#include "common/test_paths.h"

#include "deepcheck/robots/format_number.h"

#include <boost/test/unit_test.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace deepcheck::tool_test {

namespace fs = std::filesystem;

using test::readText;

/// The bundled robots and scenes (robots/data).
inline const std::string kData = test::bundledDataDir();

/// `part` occurs in `text`.
inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The outcome of one run of the binary.
struct Run {
  int status = -1;  ///< exit status; -1 when the binary did not exit normally
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// `s` as one shell word.
inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// The shell words of `args`, each quoted, separated by blanks.
inline std::string quoteAll(const std::vector<std::string>& args) {
  std::string words;
  for (const std::string& a : args) words += (words.empty() ? "" : " ") + quote(a);
  return words;
}

/// The decomposition cache (an XDG_CACHE_HOME) every scratch folder's starts from (below Scratch).
inline const fs::path& armCache();

/// A folder of its own under the temporary directory, removed at the end.
struct Scratch {
  /// How the folder's decomposition cache starts: a copy of armCache(), or empty.
  enum class Cache { Arm, Empty };

  fs::path dir;

  explicit Scratch(Cache cache = Cache::Arm) {
    static int counter = 0;
    dir =
        fs::temp_directory_path() / ("deepcheck_tool_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir);
    if (cache == Cache::Arm) fs::copy(armCache(), dir / "cache", fs::copy_options::recursive);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  /// The path of `name` in the folder.
  std::string path(const std::string& name) const { return (dir / name).string(); }

  /// Writes `text` to the file `name` of the folder; returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return path(name);
  }

  /// Runs `deepcheck <args>` with `input` on stdin, and `environment` ("NAME=value ...") added to
  /// the environment. Both are inserted into a shell command as given: quote words that need it
  /// (quote, quoteAll).
  Run run(const std::string& args, const std::string& input = "", const std::string& environment = "") const {
    const std::string in = write("stdin.txt", input);
    const std::string err = path("stderr.txt");
    const std::string cmd = "XDG_CACHE_HOME=" + quote(path("cache")) + " " + environment + " " + quote(DEEPCHECK_TOOL) +
                            " " + args + " < " + quote(in) + " 2> " + quote(err);
    Run r;
    if (FILE* pipe = ::popen(cmd.c_str(), "r")) {
      char buf[4096];
      std::size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
      const int status = ::pclose(pipe);
      r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    r.err = readText(err);
    return r;
  }
};

/// The bundled arm's meshes, decomposed by one `deepcheck info` run in a scratch folder of its own
/// on first use; removed with it at the end of the process.
inline const fs::path& armCache() {
  static const Scratch filler(Scratch::Cache::Empty);
  static const fs::path cache = [] {
    const Run r = filler.run("info " + quote(kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf") + " --package-path " +
                             quote(kData) + " --samples 0");
    // An error of the test that asked first; the others still run, decomposing the arm themselves.
    if (r.status != 0) BOOST_ERROR("filling the tests' arm cache failed (exit " << r.status << "): " << r.err);
    return fs::path(filler.path("cache"));
  }();
  return cache;
}

/// The lines of `s`, without their terminators.
inline std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

/// The blank-separated fields of `line`.
inline std::vector<std::string> fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string f;
  while (in >> f) out.push_back(f);
  return out;
}

/// The tools print numbers as the libraries write them: %.17g.
using robots::formatNumber;

/// Parses a number printed with %.17g (and checks that it was).
inline double number(const std::string& field) {
  const double v = std::strtod(field.c_str(), nullptr);
  BOOST_TEST(formatNumber(v) == field, "'" << field << "' is not printed with %.17g");
  return v;
}

}  // namespace deepcheck::tool_test
