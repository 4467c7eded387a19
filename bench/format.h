#pragma once
// What the benchmarks print in their tables: numbers, and the machine's load while they ran.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace deepcheck::bench {

/// `v` printed with the printf format `f` (one double conversion); "-" for NaN.
inline std::string fmt(double v, const char* f = "%.3g") {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// The 1, 5 and 15 minute load averages, as /proc/loadavg gives them.
inline std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace deepcheck::bench
