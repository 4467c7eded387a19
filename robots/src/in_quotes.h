// A name as the robots library's error messages quote it.
#pragma once

#include <string>

namespace deepcheck::robots::detail {

/// `s` between single quotes: 'name'.
inline std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

}  // namespace deepcheck::robots::detail
