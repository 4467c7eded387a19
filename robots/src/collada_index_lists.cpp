#include "collada_index_lists.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

namespace deepcheck::robots {
namespace {

/// How many leading bytes of a file without the .dae extension are searched for "<COLLADA".
constexpr std::size_t kColladaSignatureBytes = 4096;

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool looksLikeCollada(const std::string& path, const std::string& text) {
  if (lowercase(std::filesystem::path(path).extension().string()) == ".dae") return true;
  return lowercase(text.substr(0, kColladaSignatureBytes)).find("<collada") != std::string::npos;
}

bool isXmlSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// The name of the element whose start tag begins at text[at] == '<' ("" for an end tag,
/// a comment, CDATA or a processing instruction).
std::string_view startTagName(std::string_view text, std::size_t at) {
  std::size_t end = at + 1;
  while (end < text.size() && !isXmlSpace(text[end]) && text[end] != '>' && text[end] != '/') {
    ++end;
  }
  const std::string_view name = text.substr(at + 1, end - at - 1);
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name.front()))) return {};
  return name;
}

std::string describe(char c) {
  const auto byte = static_cast<unsigned char>(c);
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", byte);
  if (byte >= 0x21 && byte < 0x7f) return std::string("'") + c + "' (" + hex + ")";
  return std::string("byte ") + hex;
}

[[noreturn]] void reject(const std::string& path, std::string_view text, std::size_t at,
                         std::string_view list, const std::string& what) {
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  throw std::invalid_argument(
      "mesh file '" + path + "' line " + std::to_string(line) + ": COLLADA index list <" +
      std::string(list) + "> holds " + what +
      "; only non-negative integers separated by whitespace are allowed");
}

/// Checks the content of the index list whose start tag opens at text[at].
void checkList(const std::string& path, std::string_view text, std::size_t at,
               std::string_view name) {
  const std::size_t close = text.find('>', at);
  if (close == std::string_view::npos || text[close - 1] == '/') return;  // unclosed or empty
  std::size_t i = close + 1;
  for (; i < text.size() && text[i] != '<'; ++i) {
    if (!isDigit(text[i]) && !isXmlSpace(text[i])) reject(path, text, i, name, describe(text[i]));
  }
  if (i + 1 < text.size() && text[i + 1] != '/') reject(path, text, i, name, "markup");
}

}  // namespace

void checkColladaIndexLists(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!looksLikeCollada(path, text)) return;
  const std::string_view view(text);
  static constexpr std::array<std::string_view, 3> kLists{"p", "h", "vcount"};
  const std::size_t begin = view.find("<library_geometries");
  const std::size_t end = view.find("</library_geometries", begin);
  for (std::size_t at = view.find('<', begin); at < end; at = view.find('<', at + 1)) {
    const std::string_view name = startTagName(view, at);
    if (std::find(kLists.begin(), kLists.end(), name) != kLists.end()) {
      checkList(path, view, at, name);
    }
  }
}

}  // namespace deepcheck::robots
