#pragma once
// How deepcheck writes a number into a file (paths, planning scenes) or an error message: 17
// significant digits (printf's %.17g), so that reading the text back gives the same double, and
// an error names the value the caller gave rather than a rounding of it.

#include <cstdio>
#include <string>

namespace deepcheck::robots {

/// `v` with %.17g ("nan", "inf" and "-inf" for the non-finite values).
inline std::string formatNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace deepcheck::robots
