#pragma once
// Internal to deepcheck::planners: how a number appears in an error message or a written path.

#include <cstdio>
#include <string>

namespace deepcheck::planners::detail {

/// `v` with %.17g: enough digits to read the same double back.
inline std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace deepcheck::planners::detail
