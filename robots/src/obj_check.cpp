#include "obj_check.h"

#include "in_quotes.h"

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

namespace deepcheck::robots {
namespace {

/// The bytes assimp's OBJ reader ends a line at.
bool isLineEnd(char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; }

/// True when the file holds at most one line end; stops reading at the second.
bool isOneLine(std::istream& in) {
  int ends = 0;
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    if (isLineEnd(*it) && ++ends > 1) return false;
  }
  return true;
}

}  // namespace

void checkObjMeshFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char start[5] = {};
  in.read(start, sizeof start);
  std::string_view head(start, static_cast<std::size_t>(in.gcount()));
  if (!head.empty() && isLineEnd(head.front())) head.remove_prefix(1);
  if (head.substr(0, 3) == "\xEF\xBB\xBF") head.remove_prefix(3);
  if (head.empty() || (head.front() != 'f' && head.front() != 'l' && head.front() != 'p')) return;
  in.clear();
  in.seekg(0);
  if (!isOneLine(in)) return;
  throw std::invalid_argument("mesh file " + detail::inQuotes(path) + " is one line, an OBJ '" +
                              std::string(1, head.front()) +
                              "' statement: an OBJ mesh needs 'v' (vertex) and 'f' (face) statements on "
                              "separate lines");
}

}  // namespace deepcheck::robots
