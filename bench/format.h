#pragma once
// How the benchmarks print numbers in their tables.

#include <cmath>
#include <cstdio>
#include <string>

namespace deepcheck::bench {

/// `v` printed with the printf format `f` (one double conversion); "-" for NaN.
inline std::string fmt(double v, const char* f = "%.3g") {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace deepcheck::bench
