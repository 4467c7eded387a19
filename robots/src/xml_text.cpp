// TinyXML parsing of checked UTF-8 text (xml_text.h).

#include "xml_text.h"

#include "deepcheck/robots/robot_model.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace {

/// Length of the valid UTF-8 sequence starting at s[i], or 0 when there is none (RFC 3629).
std::size_t utf8SequenceLength(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  if (b < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80;  // allowed range of the second byte
  unsigned char hi = 0xBF;
  if (b >= 0xC2 && b <= 0xDF) {
    n = 2;
  } else if (b >= 0xE0 && b <= 0xEF) {
    n = 3;
    if (b == 0xE0) lo = 0xA0;  // no overlong forms
    if (b == 0xED) hi = 0x9F;  // no surrogates
  } else if (b >= 0xF0 && b <= 0xF4) {
    n = 4;
    if (b == 0xF0) lo = 0x90;  // no overlong forms
    if (b == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return n;
}

void checkText(const std::string& xml, const std::string& context) {
  int line = 1;
  for (std::size_t i = 0; i < xml.size();) {
    const std::size_t n = xml[i] == '\0' ? 0 : utf8SequenceLength(xml, i);
    if (n == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(xml[i]));
      std::ostringstream msg;
      msg << context << ": line " << line << ", byte " << i << " (" << hex
          << "): " << (xml[i] == '\0' ? "a NUL byte" : "not UTF-8") << "; URDF and SRDF files must be UTF-8 text";
      throw std::invalid_argument(msg.str());
    }
    if (xml[i] == '\n') ++line;
    i += n;
  }
}

int lineAt(std::string_view xml, std::size_t at) {
  return 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + static_cast<long>(at), '\n'));
}

/// Position of the '>' closing the start tag that begins at xml[at] ('<'), npos when none. A
/// quote opens a value only right after '=' (TinyXML reads unquoted values up to a space, '/'
/// or '>').
std::size_t startTagEnd(std::string_view xml, std::size_t at) {
  bool afterEquals = false;
  for (std::size_t i = at + 1; i < xml.size(); ++i) {
    const char c = xml[i];
    if (c == '>') return i;
    if (afterEquals && (c == '"' || c == '\'')) {
      i = xml.find(c, i + 1);
      if (i == std::string_view::npos) return i;
      afterEquals = false;
    } else if (c == '=') {
      afterEquals = true;
    } else if (!isXmlSpace(c)) {
      afterEquals = false;
    }
  }
  return std::string_view::npos;
}

/// Position just past `terminator`, searched from `from`; npos when absent.
std::size_t pastTerminator(std::string_view xml, std::size_t from, std::string_view terminator) {
  const std::size_t at = xml.find(terminator, from);
  return at == std::string_view::npos ? at : at + terminator.size();
}

}  // namespace

void checkXmlDepth(std::string_view xml, const std::string& context) {
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw std::invalid_argument(context + ": line " + std::to_string(lineAt(xml, at)) + ": " + what);
  };
  const auto startsAt = [&](std::size_t at, std::string_view s) { return xml.compare(at, s.size(), s) == 0; };
  int depth = 0;
  for (std::size_t at = xml.find('<'); at != std::string_view::npos; at = xml.find('<', at)) {
    std::size_t end = std::string_view::npos;  // just past the markup
    if (startsAt(at, "<!--")) {
      end = pastTerminator(xml, at + 4, "-->");
    } else if (startsAt(at, "<![CDATA[")) {
      end = pastTerminator(xml, at + 9, "]]>");
    } else if (startsAt(at, "<?") || startsAt(at, "<!")) {
      end = pastTerminator(xml, at, ">");
      if (end == std::string_view::npos) return;  // unclosed: the parser reports it
      const std::string_view markup = xml.substr(at, end - at);
      if (markup[1] == '?' ? markup.size() < 4 || markup[markup.size() - 2] != '?'
                           : markup.find('[') != std::string_view::npos) {
        fail(at,
             "a processing instruction or declaration holding '>' or an internal DTD subset, "
             "which is not supported");
      }
    } else if (startsAt(at, "</")) {
      depth = std::max(0, depth - 1);
      end = pastTerminator(xml, at, ">");
    } else {
      end = startTagEnd(xml, at);
      if (end == std::string_view::npos) return;
      if (xml[end - 1] != '/' && ++depth > kMaxNestingDepth) {
        fail(at, "elements nested " + std::to_string(depth) + " levels deep, more than the limit of " +
                     std::to_string(kMaxNestingDepth));
      }
      ++end;
    }
    if (end == std::string_view::npos) return;
    at = end;
  }
}

void parseXml(TiXmlDocument& doc, const std::string& xml, const std::string& context) {
  checkText(xml, context);
  checkXmlDepth(xml, context);
  doc.Parse(xml.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error()) {
    std::ostringstream msg;
    msg << context << ": malformed XML at line " << doc.ErrorRow() << ", column " << doc.ErrorCol() << ": "
        << doc.ErrorDesc();
    throw std::invalid_argument(msg.str());
  }
}

const TiXmlElement& parseSrdfRoot(TiXmlDocument& doc, const std::string& xml, const std::string& context) {
  parseXml(doc, xml, context);
  const TiXmlElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Value()) != "robot") {
    throw std::invalid_argument(context + ": the root element is not <robot>");
  }
  return *robot;
}

std::string readSrdfText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("SRDF '" + path + "': cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::invalid_argument("SRDF '" + path + "': cannot read the file");
  return text.str();
}

}  // namespace deepcheck::robots
