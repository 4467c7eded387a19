#include "obj_check.h"

#include "in_quotes.h"

#include <cstddef>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

namespace deepcheck::robots {
namespace {

/// How many bytes firstCharacter looks at: a line end, a byte order mark (3 bytes), a character.
constexpr std::size_t kStartBytes = 5;

/// The bytes assimp's OBJ reader ends a line at.
bool isLineEnd(char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; }

/// The first character of the first line: after a leading line end and a UTF-8 byte order mark.
char firstCharacter(std::string_view start) {
  if (!start.empty() && isLineEnd(start.front())) start.remove_prefix(1);
  if (start.substr(0, 3) == "\xEF\xBB\xBF") start.remove_prefix(3);
  return start.empty() ? '\0' : start.front();
}

}  // namespace

void checkObjMeshFile(const std::string& path) {
  // One pass: the first kStartBytes bytes, stopping at the second line end.
  std::ifstream in(path, std::ios::binary);
  std::string start;
  int ends = 0;
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    if (start.size() < kStartBytes) start += *it;
    if (isLineEnd(*it) && ++ends > 1) return;
  }
  const char statement = firstCharacter(start);
  if (statement != 'f' && statement != 'l' && statement != 'p') return;
  throw std::invalid_argument("mesh file " + detail::inQuotes(path) + " is one line, an OBJ '" +
                              std::string(1, statement) +
                              "' statement: an OBJ mesh needs 'v' (vertex) and 'f' (face) statements on "
                              "separate lines");
}

}  // namespace deepcheck::robots
