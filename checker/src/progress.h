#pragma once
// Progress of a long step of the world's construction, as lines on a stream (stderr by default,
// WorldOptions::progress): nothing while the step is short, so a quick load prints nothing.
// After tol::kProgressQuietSeconds a line "deepcheck: <what> <done>/<total> (<s> s, about <r> s
// left)" (r: the rest at the pace so far; no total and no estimate when the total is not known in
// advance: 0) at most that often, and a closing line "deepcheck: <what> done (<s> s)" when any line was printed.

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace deepcheck::checker::detail {

class Progress {
 public:
  /// `out` null: silent. `quietSeconds`: how long the step runs before the first line, and the
  /// least time between two lines.
  Progress(std::ostream* out, std::string what, std::size_t total, double quietSeconds);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress();

  /// `done` of `total` items are finished.
  void update(std::size_t done);

 private:
  double elapsed() const;

  std::ostream* out_;
  std::string what_;
  std::size_t total_;
  double quiet_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double lastLine_ = 0.0;  // seconds since start of the last line printed
  bool printed_ = false;
};

}  // namespace deepcheck::checker::detail
