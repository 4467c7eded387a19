// TinyXML parsing of checked UTF-8 text (xml_text.h).

#include "xml_text.h"

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
      msg << context << ": line " << line << ", byte " << i << " (" << hex << "): "
          << (xml[i] == '\0' ? "a NUL byte" : "not UTF-8") << "; URDF and SRDF files must be UTF-8 text";
      throw std::invalid_argument(msg.str());
    }
    if (xml[i] == '\n') ++line;
    i += n;
  }
}

}  // namespace

void parseXml(TiXmlDocument& doc, const std::string& xml, const std::string& context) {
  checkText(xml, context);
  doc.Parse(xml.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error()) {
    std::ostringstream msg;
    msg << context << ": malformed XML at line " << doc.ErrorRow() << ", column " << doc.ErrorCol()
        << ": " << doc.ErrorDesc();
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
