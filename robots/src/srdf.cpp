#include "deepcheck/robots/srdf.h"

#include "xml_text.h"
#include "in_quotes.h"

#include <tinyxml.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {

using detail::inQuotes;

const char* toString(DisableReason reason) {
  switch (reason) {
    case DisableReason::Adjacent:
      return "Adjacent";
    case DisableReason::Default:
      return "Default";
    case DisableReason::Always:
      return "Always";
    case DisableReason::Never:
      return "Never";
    case DisableReason::User:
      return "User";
    case DisableReason::Unspecified:
      return "";
    case DisableReason::Other:
      return "Other";
  }
  return "";
}

DisableReason parseDisableReason(const std::string& text) {
  for (int r = 0; r < kNumDisableReasons; ++r) {
    const auto reason = static_cast<DisableReason>(r);
    if (text == toString(reason)) return reason;
  }
  return DisableReason::Other;
}

std::string reasonText(const DisabledPair& pair) {
  return pair.reason == DisableReason::Other ? pair.reasonText : toString(pair.reason);
}

std::pair<std::string, std::string> pairKey(const std::string& a, const std::string& b) {
  return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
}

namespace {

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::vector<DisabledPair> parseSrdfDisabledPairs(const std::string& xml, const std::string& sourceName) {
  const std::string context = "SRDF " + inQuotes(sourceName.empty() ? "<string>" : sourceName);
  TiXmlDocument doc;
  const TiXmlElement& robot = parseSrdfRoot(doc, xml, context);
  std::vector<DisabledPair> pairs;
  for (const TiXmlElement* e = robot.FirstChildElement("disable_collisions"); e != nullptr;
       e = e->NextSiblingElement("disable_collisions")) {
    const std::string where = context + ", line " + std::to_string(e->Row());
    DisabledPair p;
    for (const char* attr : {"link1", "link2"}) {
      const char* value = e->Attribute(attr);
      if (value == nullptr || *value == '\0') {
        throw std::invalid_argument(where + ": <disable_collisions> without " + attr);
      }
      (std::string(attr) == "link1" ? p.link1 : p.link2) = value;
    }
    const char* reason = e->Attribute("reason");
    p.reason = parseDisableReason(reason == nullptr ? "" : reason);
    if (p.reason == DisableReason::Other) p.reasonText = reason;
    pairs.push_back(p);
  }
  return pairs;
}

std::vector<DisabledPair> readSrdfDisabledPairs(const std::string& path) {
  return parseSrdfDisabledPairs(readSrdfText(path), path);
}

std::vector<SrdfVirtualJoint> parseSrdfVirtualJoints(const std::string& xml, const std::string& sourceName) {
  const std::string context = "SRDF " + inQuotes(sourceName.empty() ? "<string>" : sourceName);
  TiXmlDocument doc;
  const TiXmlElement& robot = parseSrdfRoot(doc, xml, context);
  std::vector<SrdfVirtualJoint> joints;
  for (const TiXmlElement* e = robot.FirstChildElement("virtual_joint"); e != nullptr;
       e = e->NextSiblingElement("virtual_joint")) {
    const std::string where = context + ", line " + std::to_string(e->Row());
    SrdfVirtualJoint j;
    j.line = e->Row();
    for (auto [attr, field] : {std::pair<const char*, std::string*>{"name", &j.name},
                               {"type", &j.type},
                               {"parent_frame", &j.parentFrame},
                               {"child_link", &j.childLink}}) {
      const char* value = e->Attribute(attr);
      if (value == nullptr || *value == '\0') {
        throw std::invalid_argument(where + ": <virtual_joint> without " + attr);
      }
      *field = value;
    }
    if (j.type != "fixed" && j.type != "floating" && j.type != "planar") {
      throw std::invalid_argument(where + ": <virtual_joint> " + inQuotes(j.name) + " has type " + inQuotes(j.type) +
                                  " (known: fixed, floating, planar)");
    }
    joints.push_back(j);
  }
  return joints;
}

std::vector<SrdfVirtualJoint> readSrdfVirtualJoints(const std::string& path) {
  return parseSrdfVirtualJoints(readSrdfText(path), path);
}

std::string srdfText(const std::string& robotName, const std::vector<DisabledPair>& pairs, const std::string& comment) {
  SrdfContents contents;
  contents.pairs = pairs;
  return srdfText(robotName, contents, comment);
}

namespace {

/// <tag attr="value"/> lines of a group, indented four spaces.
void writeGroupElements(std::ostringstream& out, const char* tag, const std::vector<std::string>& names) {
  for (const std::string& n : names) out << "    <" << tag << " name=\"" << xmlEscape(n) << "\"/>\n";
}

void writeGroup(std::ostringstream& out, const SrdfGroup& g) {
  out << "  <group name=\"" << xmlEscape(g.name) << "\">\n";
  writeGroupElements(out, "joint", g.joints);
  writeGroupElements(out, "link", g.links);
  for (const auto& [base, tip] : g.chains) {
    out << "    <chain base_link=\"" << xmlEscape(base) << "\" tip_link=\"" << xmlEscape(tip) << "\"/>\n";
  }
  writeGroupElements(out, "group", g.subgroups);
  out << "  </group>\n";
}

}  // namespace

std::string srdfText(const std::string& robotName, const SrdfContents& contents, const std::string& comment) {
  const std::vector<DisabledPair>& pairs = contents.pairs;
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  if (!comment.empty()) {
    // "--" may not appear inside an XML comment.
    std::string safe = comment;
    for (std::size_t k = safe.find("--"); k != std::string::npos; k = safe.find("--", k)) {
      safe.replace(k, 2, "- -");
    }
    out << "<!-- " << safe << " -->\n";
  }
  out << "<robot name=\"" << xmlEscape(robotName) << "\">\n";
  for (const SrdfGroup& g : contents.groups) writeGroup(out, g);
  for (const SrdfVirtualJoint& j : contents.virtualJoints) {
    out << "  <virtual_joint name=\"" << xmlEscape(j.name) << "\" type=\"" << xmlEscape(j.type) << "\" parent_frame=\""
        << xmlEscape(j.parentFrame) << "\" child_link=\"" << xmlEscape(j.childLink) << "\"/>\n";
  }
  for (const DisabledPair& p : pairs) {
    out << "  <disable_collisions link1=\"" << xmlEscape(p.link1) << "\" link2=\"" << xmlEscape(p.link2) << "\"";
    if (p.reason != DisableReason::Unspecified) {
      out << " reason=\"" << xmlEscape(reasonText(p)) << "\"";
    }
    out << "/>\n";
  }
  out << "</robot>\n";
  return out.str();
}

void writeSrdf(const std::string& path, const std::string& robotName, const std::vector<DisabledPair>& pairs,
               const std::string& comment) {
  SrdfContents contents;
  contents.pairs = pairs;
  writeSrdf(path, robotName, contents, comment);
}

void writeSrdf(const std::string& path, const std::string& robotName, const SrdfContents& contents,
               const std::string& comment) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::invalid_argument("SRDF " + inQuotes(path) + ": cannot open for writing");
  out << srdfText(robotName, contents, comment);
  out.close();
  if (!out) throw std::invalid_argument("SRDF " + inQuotes(path) + ": write failed");
}

}  // namespace deepcheck::robots
