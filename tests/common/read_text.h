#pragma once
// A whole file as one string, for the tests that read back what was written.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace deepcheck::test {

/// The bytes of the file at `path`; empty when it cannot be read.
inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace deepcheck::test
