#pragma once
// Command-line options of the benchmarks: one loop for every benchmark's options.

#include <stdexcept>
#include <string>

namespace deepcheck::bench {

/// Prints the error (none: just the usage) and the usage, and exits with status 2.
using Usage = void (*)(const std::string& error);

/// Calls handle(arg, value) for every argument; value() returns the next argument (a usage error
/// when there is none). handle returns false for an option it does not know (a usage error naming
/// it). --help and -h print the usage. std::invalid_argument and std::out_of_range thrown by
/// handle (std::stoi, std::stod, a name it does not know) are usage errors naming the option.
template <class Handle>
void readOptions(int argc, char** argv, Usage usage, Handle handle) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") usage("");
    try {
      if (!handle(arg, value)) usage("unknown option '" + arg + "'");
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      usage("bad value for " + arg + (what.find(' ') != std::string::npos ? ": " + what : ""));
    } catch (const std::out_of_range&) {
      usage("bad value for " + arg);
    }
  }
}

/// `text` as a whole number >= 1 (a usage error naming `option` otherwise).
inline int positiveCount(const std::string& text, const std::string& option, Usage usage) {
  const int n = std::stoi(text);
  if (n < 1) usage(option + " must be at least 1");
  return n;
}

/// `text` as a number > 0 (a usage error naming `option` otherwise).
inline double positiveValue(const std::string& text, const std::string& option, Usage usage) {
  const double v = std::stod(text);
  if (!(v > 0.0)) usage(option + " must be positive");
  return v;
}

}  // namespace deepcheck::bench
