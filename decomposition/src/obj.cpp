// Writing convex pieces as a Wavefront OBJ file (decomposition.h, writePiecesObj).

#include "deepcheck/decomposition/decomposition.h"

#include <fstream>
#include <stdexcept>
#include <string>

namespace deepcheck::decomposition {

using Eigen::Vector3d;

void writePiecesObj(const std::string& path, const std::vector<ConvexPiece>& pieces) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("writePiecesObj: cannot open '" + path + "' for writing");
  out.precision(17);
  out << "# deepcheck convex decomposition: " << pieces.size() << " pieces\n";
  int base = 1;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    out << "o piece_" << i << "\n";
    for (const Vector3d& v : pieces[i].vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << "\n";
    for (const auto& t : pieces[i].triangles) {
      out << "f " << base + t[0] << ' ' << base + t[1] << ' ' << base + t[2] << "\n";
    }
    base += static_cast<int>(pieces[i].vertices.size());
  }
  out.flush();
  if (!out) throw std::runtime_error("writePiecesObj: error while writing '" + path + "'");
}

}  // namespace deepcheck::decomposition
