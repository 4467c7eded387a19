#include "collada_check.h"

#include "xml_text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace deepcheck::robots {
namespace {

/// How many leading bytes of a mesh file are read to tell whether it is XML, and COLLADA.
constexpr std::size_t kSignatureBytes = 4096;

/// Extensions of the XML formats assimp reads without decompressing them.
constexpr std::array<std::string_view, 7> kXmlExtensions{".dae", ".xml", ".x3d", ".amf", ".irr", ".irrmesh", ".xgl"};

constexpr std::array<std::string_view, 3> kIndexLists{"p", "h", "vcount"};
constexpr std::array<std::string_view, 7> kArrays{"float_array", "int_array",    "bool_array", "Name_array",
                                                  "IDREF_array", "SIDREF_array", "token_array"};

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// The first kSignatureBytes of the file.
std::string head(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text(kSignatureBytes, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

/// True for an XML extension, or when the first byte after white space (and a UTF-8 byte order
/// mark) is '<'.
bool looksLikeXml(const std::string& extension, std::string_view start) {
  if (std::find(kXmlExtensions.begin(), kXmlExtensions.end(), extension) != kXmlExtensions.end()) return true;
  if (start.substr(0, 3) == "\xEF\xBB\xBF") start.remove_prefix(3);
  const std::size_t first = start.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && start[first] == '<';
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }

template <std::size_t N>
bool isOneOf(std::string_view name, const std::array<std::string_view, N>& names) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// One start tag: text[at] == '<', text[end] == '>' (npos when the tag is not closed).
struct StartTag {
  std::string_view name;
  std::size_t at = 0, end = std::string_view::npos;
};

/// The start tag beginning at text[at] == '<'; an empty name for an end tag, a comment, CDATA or
/// a processing instruction. The end is found outside quoted attribute values.
StartTag startTag(std::string_view text, std::size_t at) {
  StartTag tag;
  tag.at = at;
  std::size_t i = at + 1;
  while (i < text.size() && !isXmlSpace(text[i]) && text[i] != '>' && text[i] != '/') ++i;
  const std::string_view name = text.substr(at + 1, i - at - 1);
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name.front()))) return tag;
  tag.name = name;
  for (char quote = 0; i < text.size(); ++i) {
    if (quote != 0) {
      if (text[i] == quote) quote = 0;
    } else if (text[i] == '"' || text[i] == '\'') {
      quote = text[i];
    } else if (text[i] == '>') {
      tag.end = i;
      break;
    }
  }
  return tag;
}

/// The value of attribute `name` in the start tag (without quotes), if present.
std::optional<std::string_view> attribute(std::string_view text, const StartTag& tag, std::string_view name) {
  if (tag.end == std::string_view::npos) return std::nullopt;
  const std::string_view inside = text.substr(tag.at, tag.end - tag.at);
  for (std::size_t i = 1 + tag.name.size(); i < inside.size();) {
    while (i < inside.size() && isXmlSpace(inside[i])) ++i;
    const std::size_t nameBegin = i;
    while (i < inside.size() && inside[i] != '=' && !isXmlSpace(inside[i]) && inside[i] != '/') ++i;
    const std::string_view key = inside.substr(nameBegin, i - nameBegin);
    while (i < inside.size() && isXmlSpace(inside[i])) ++i;
    if (i >= inside.size() || inside[i] != '=') return std::nullopt;  // malformed: assimp's to report
    ++i;
    while (i < inside.size() && isXmlSpace(inside[i])) ++i;
    if (i >= inside.size() || (inside[i] != '"' && inside[i] != '\'')) return std::nullopt;
    const std::size_t close = inside.find(inside[i], i + 1);
    if (close == std::string_view::npos) return std::nullopt;
    if (key == name) return inside.substr(i + 1, close - i - 1);
    i = close + 1;
  }
  return std::nullopt;
}

/// A non-negative integer (digits, optional surrounding whitespace) of at most 18 digits.
std::optional<std::uint64_t> parseCount(std::string_view s) {
  while (!s.empty() && isXmlSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isXmlSpace(s.back())) s.remove_suffix(1);
  if (s.empty() || s.size() > 18 || !std::all_of(s.begin(), s.end(), isDigit)) return std::nullopt;
  std::uint64_t v = 0;
  for (char c : s) v = 10 * v + static_cast<std::uint64_t>(c - '0');
  return v;
}

std::string describe(char c) {
  const auto byte = static_cast<unsigned char>(c);
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", byte);
  if (byte >= 0x21 && byte < 0x7f) return std::string("'") + c + "' (" + hex + ")";
  return std::string("byte ") + hex;
}

class Checker {
 public:
  Checker(const std::string& path, std::string_view text) : path_(path), text_(text) {}

  void run() {
    const std::size_t geometriesBegin = text_.find("<library_geometries");
    const std::size_t geometriesEnd = text_.find("</library_geometries", geometriesBegin);
    for (std::size_t at = text_.find('<'); at != std::string_view::npos; at = text_.find('<', at + 1)) {
      const StartTag tag = startTag(text_, at);
      if (tag.name.empty()) continue;
      if (isOneOf(tag.name, kIndexLists) && at > geometriesBegin && at < geometriesEnd) checkIndexList(tag);
      if (isOneOf(tag.name, kArrays)) addArray(tag);
      if (tag.name == "accessor") accessors_.push_back(tag);  // checked once every array is known
    }
    for (const StartTag& tag : accessors_) checkAccessor(tag);
  }

 private:
  [[noreturn]] void reject(std::size_t at, const std::string& what) const {
    const auto line = 1 + std::count(text_.begin(), text_.begin() + static_cast<long>(at), '\n');
    throw std::invalid_argument("mesh file '" + path_ + "' line " + std::to_string(line) + ": COLLADA " + what);
  }

  std::string named(const StartTag& tag) const {
    const auto id = attribute(text_, tag, "id");
    return "<" + std::string(tag.name) + ">" + (id ? " '" + std::string(*id) + "'" : std::string());
  }

  void checkIndexList(const StartTag& tag) const {
    if (tag.end == std::string_view::npos || text_[tag.end - 1] == '/') return;  // unclosed or empty
    const std::string list = "index list <" + std::string(tag.name) + "> holds ";
    const char* const allowed = "; only non-negative integers separated by whitespace are allowed";
    std::size_t i = tag.end + 1;
    for (; i < text_.size() && text_[i] != '<'; ++i) {
      if (!isDigit(text_[i]) && !isXmlSpace(text_[i])) reject(i, list + describe(text_[i]) + allowed);
    }
    if (i + 1 < text_.size() && text_[i + 1] != '/') reject(i, list + "markup" + allowed);
  }

  void addArray(const StartTag& tag) {
    const auto count = attribute(text_, tag, "count");
    if (!count) reject(tag.at, named(tag) + " has no count attribute");
    const auto n = parseCount(*count);
    if (!n) reject(tag.at, named(tag) + " has count \"" + std::string(*count) + "\", not a non-negative integer");
    if (const auto id = attribute(text_, tag, "id")) arrays_[*id] = *n;
  }

  /// An accessor of an array of this file must lie inside it.
  void checkAccessor(const StartTag& tag) const {
    const auto source = attribute(text_, tag, "source");
    if (!source || source->empty() || source->front() != '#') return;
    const auto array = arrays_.find(source->substr(1));
    if (array == arrays_.end()) return;  // an unresolved source is assimp's to report
    const auto number = [&](std::string_view key, std::uint64_t fallback) {
      const auto value = attribute(text_, tag, key);
      if (!value) return fallback;
      const auto n = parseCount(*value);
      if (!n)
        reject(tag.at, "<accessor> of '" + std::string(*source) + "' has " + std::string(key) + " \"" +
                           std::string(*value) + "\", not a non-negative integer");
      return *n;
    };
    if (!attribute(text_, tag, "count"))
      reject(tag.at, "<accessor> of '" + std::string(*source) + "' has no count attribute");
    const std::uint64_t count = number("count", 0), stride = number("stride", 1), offset = number("offset", 0);
    const unsigned __int128 needed = static_cast<unsigned __int128>(count) * stride + offset;
    if (needed > array->second) {
      reject(tag.at, "<accessor> of '" + std::string(*source) + "' reads " + std::to_string(count) + " x " +
                         std::to_string(stride) + " values from offset " + std::to_string(offset) +
                         ", beyond the array's " + std::to_string(array->second));
    }
  }

  const std::string& path_;
  std::string_view text_;
  std::map<std::string_view, std::uint64_t> arrays_;
  std::vector<StartTag> accessors_;
};

}  // namespace

void checkXmlMeshFile(const std::string& path) {
  const std::string extension = lowercase(std::filesystem::path(path).extension().string());
  const std::string start = head(path);
  if (!looksLikeXml(extension, start)) return;  // an STL or OBJ file is not read a second time
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  checkXmlDepth(text, "mesh file '" + path + "'");
  if (extension == ".dae" || lowercase(start).find("<collada") != std::string::npos) Checker(path, text).run();
}

}  // namespace deepcheck::robots
