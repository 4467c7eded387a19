#pragma once
// Parsing URDF and SRDF text with TinyXML, after checking that it is text TinyXML can read safely.

#include <tinyxml.h>

#include <string>
#include <string_view>

namespace deepcheck::robots {

/// XML white space (space, tab, line feed, carriage return).
inline bool isXmlSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// Throws std::invalid_argument "<context>: line L: elements nested N levels deep, more than the
/// limit of kMaxNestingDepth" when an element of `xml` lies deeper than kMaxNestingDepth (the
/// root element is level 1). TinyXML, urdfdom and assimp's XML readers recurse once per level, so
/// this runs on the text before any of them does. The scan follows XML's rules for comments,
/// CDATA sections and quoted attribute values; a processing instruction or a <!...> declaration
/// holding a '>' before its end (a DOCTYPE internal subset) is rejected too, as TinyXML ends
/// those at the first '>' where other parsers do not, so no single reading of the text would hold
/// for both.
void checkXmlDepth(std::string_view xml, const std::string& context);

/// Parses `xml` into `doc` (UTF-8). Throws std::invalid_argument starting with `context`:
///  - for a NUL byte or a byte sequence that is not UTF-8 (RFC 3629: no overlong forms, no
///    surrogates, nothing above U+10FFFF), naming the line and byte offset. TinyXML 2.6 skips the
///    whole length a lead byte announces, so a sequence truncated at the end of the text makes it
///    read past the end of the buffer; such text is rejected before it is parsed;
///  - for elements nested deeper than kMaxNestingDepth (checkXmlDepth);
///  - for malformed XML, with TinyXML's line, column and message.
void parseXml(TiXmlDocument& doc, const std::string& xml, const std::string& context);

/// parseXml, then the <robot> root element of SRDF text; throws std::invalid_argument starting
/// with `context` when the root is another element.
const TiXmlElement& parseSrdfRoot(TiXmlDocument& doc, const std::string& xml, const std::string& context);

/// The whole of an SRDF file as text; throws std::invalid_argument ("SRDF '<path>': cannot open
/// the file" / "cannot read the file").
std::string readSrdfText(const std::string& path);

}  // namespace deepcheck::robots
