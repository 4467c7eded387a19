#pragma once
// Parsing URDF and SRDF text with TinyXML, after checking that it is text TinyXML can read safely.

#include <tinyxml.h>

#include <string>

namespace deepcheck::robots {

/// Parses `xml` into `doc` (UTF-8). Throws std::invalid_argument starting with `context`:
///  - for a NUL byte or a byte sequence that is not UTF-8 (RFC 3629: no overlong forms, no
///    surrogates, nothing above U+10FFFF), naming the line and byte offset. TinyXML 2.6 skips the
///    whole length a lead byte announces, so a sequence truncated at the end of the text makes it
///    read past the end of the buffer; such text is rejected before it is parsed;
///  - for malformed XML, with TinyXML's line, column and message.
void parseXml(TiXmlDocument& doc, const std::string& xml, const std::string& context);

/// parseXml, then the <robot> root element of SRDF text; throws std::invalid_argument starting
/// with `context` when the root is another element.
const TiXmlElement& parseSrdfRoot(TiXmlDocument& doc, const std::string& xml, const std::string& context);

/// The whole of an SRDF file as text; throws std::invalid_argument ("SRDF '<path>': cannot open
/// the file" / "cannot read the file").
std::string readSrdfText(const std::string& path);

}  // namespace deepcheck::robots
