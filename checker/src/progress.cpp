#include "progress.h"

#include <cstdio>
#include <utility>

namespace deepcheck::checker::detail {

namespace {

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f s", s);
  return buf;
}

}  // namespace

Progress::Progress(std::ostream* out, std::string what, std::size_t total, double quietSeconds)
    : out_(out), what_(std::move(what)), total_(total), quiet_(quietSeconds) {}

Progress::~Progress() {
  if (printed_) *out_ << "deepcheck: " << what_ << " done (" << seconds(elapsed()) << ")\n" << std::flush;
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(std::size_t done) {
  if (out_ == nullptr) return;
  const double now = elapsed();
  if (now < quiet_ || (printed_ && now - lastLine_ < quiet_)) return;
  *out_ << "deepcheck: " << what_ << " " << done;
  if (total_ > 0) *out_ << "/" << total_;
  *out_ << " (" << seconds(now);
  // The rest at the pace so far: an estimate, for steps whose items take alike times.
  if (total_ > 0 && done > 0 && done < total_) {
    *out_ << ", about " << seconds(now * static_cast<double>(total_ - done) / static_cast<double>(done)) << " left";
  }
  *out_ << ")\n" << std::flush;
  lastLine_ = now;
  printed_ = true;
}

}  // namespace deepcheck::checker::detail
