#pragma once
// The CSV a benchmark writes beside its printed table.

#include <cstdio>
#include <cstdlib>
#include <string>

namespace deepcheck::bench {

/// Opens `path` for the CSV of `program` and writes its header line; on failure prints a message
/// naming both and exits with status 1. The caller closes it.
inline std::FILE* openCsv(const char* program, const std::string& path, const char* header) {
  std::FILE* csv = std::fopen(path.c_str(), "w");
  if (!csv) {
    std::fprintf(stderr, "%s: cannot write %s (run from the source tree, or give --csv FILE)\n", program, path.c_str());
    std::exit(1);
  }
  std::fprintf(csv, "%s\n", header);
  return csv;
}

}  // namespace deepcheck::bench
