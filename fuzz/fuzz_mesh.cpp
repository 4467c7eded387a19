// Fuzz harness: mesh file bytes through the project's loader (robots::loadMesh, assimp inside).
// The first byte picks the file type by extension (STL, OBJ or COLLADA), the rest is the file:
// it is written to a temporary file because loadMesh, like URDF meshes, reads a path. Bad input
// must end in an exception naming the file, never a crash; a loaded mesh must be finite.

#include "deepcheck/robots/mesh_loader.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

const char* const kExtensions[] = {".stl", ".obj", ".dae"};

std::string tempPath(const char* extension) {
  return (std::filesystem::temp_directory_path() / ("deepcheck_fuzz_mesh_" + std::to_string(::getpid()) + extension))
      .string();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string path = tempPath(kExtensions[data[0] % 3]);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const deepcheck::robots::TriangleMesh mesh = deepcheck::robots::loadMesh(path);
    for (const Eigen::Vector3d& v : mesh.vertices) {
      if (!v.allFinite()) {
        std::fprintf(stderr, "loadMesh returned a non-finite vertex\n");
        std::abort();
      }
    }
  } catch (const std::exception&) {
    // Rejected input.
  }
  std::remove(path.c_str());
  return 0;
}
