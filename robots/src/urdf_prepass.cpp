// The TinyXML pass over a URDF before urdfdom reads it (urdf_prepass.h).

#include "urdf_prepass.h"

#include "in_quotes.h"
#include "xml_text.h"

#include "deepcheck/geometry/input_range.h"

#include <tinyxml.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace deepcheck::robots::detail {
namespace {

std::string attribute(const TiXmlElement& e, const char* name) {
  const char* value = e.Attribute(name);
  return value == nullptr ? std::string() : std::string(value);
}

/// The TinyXML pass: syntax, finiteness of every number we use, and removal of what we never
/// read (<visual>, <inertial>).
class Prepass {
 public:
  Prepass(std::string context, int maxLinks) : context_(std::move(context)), maxLinks_(maxLinks) {}

  /// Returns the cleaned XML text for urdfdom; fills jointOrder (joint name -> position in file)
  /// and visualLinks (the links with a <visual>, which the cleaned text no longer shows).
  std::string run(const std::string& xml, std::map<std::string, int>& jointOrder, std::set<std::string>& visualLinks) {
    TiXmlDocument doc;
    parseXml(doc, xml, context_);
    TiXmlElement* robot = doc.RootElement();
    if (robot == nullptr || std::string(robot->Value()) != "robot") {
      throw std::invalid_argument(context_ + ": the root element is not <robot>");
    }
    checkCounts(*robot);
    int jointCount = 0;
    std::map<std::string, JointLinks> parentOf;  // child link -> its joint
    for (TiXmlElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string tag = e->Value();
      if (tag == "link") {
        if (e->FirstChildElement("visual") != nullptr) visualLinks.insert(attribute(*e, "name"));
        checkLink(*e);
      } else if (tag == "joint") {
        checkJoint(*e);
        addToTree(*e, parentOf);
        jointOrder.emplace(attribute(*e, "name"), jointCount++);
      }
    }
    checkNoLoop(parentOf);
    TiXmlPrinter printer;
    doc.Accept(&printer);
    return printer.CStr();
  }

 private:
  /// Throws when the robot holds more than maxLinks_ links or joints.
  void checkCounts(const TiXmlElement& robot) const {
    for (const char* tag : {"link", "joint"}) {
      int n = 0;
      for (const TiXmlElement* e = robot.FirstChildElement(tag); e != nullptr; e = e->NextSiblingElement(tag)) ++n;
      if (n > maxLinks_) {
        throw std::invalid_argument(context_ + ": " + std::to_string(n) + " <" + tag + "> elements, more than " +
                                    "LoadOptions::maxLinks = " + std::to_string(maxLinks_) +
                                    " (raise it to load the file)");
      }
    }
  }

  /// Parses attribute `attr` of `e` as `count` numbers (count < 0: any count >= 1); throws
  /// naming `owner` and `what` when one is not a number or not finite.
  void checkNumbers(const TiXmlElement& e, const char* attr, int count, const std::string& owner,
                    const std::string& what) const {
    const char* text = e.Attribute(attr);
    if (text == nullptr) return;  // absent: urdfdom's default (or its own error)
    const std::string where = context_ + ", " + owner + ": " + what + " " + attr + "=\"" + text + "\"";
    const char* p = text;
    int n = 0;
    while (true) {
      while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
      if (*p == '\0') break;
      char* end = nullptr;
      const double value = std::strtod(p, &end);
      if (end == p) throw std::invalid_argument(where + " is not a list of numbers");
      if (!(std::abs(value) <= geometry::range::kMaxCoordinate)) {
        std::ostringstream msg;
        msg << where << " has a " << (std::isfinite(value) ? "value out of range" : "non-finite value")
            << " (component " << n << "; magnitudes up to " << geometry::range::kMaxCoordinate << " are supported)";
        throw std::invalid_argument(msg.str());
      }
      ++n;
      p = end;
    }
    if ((count > 0 && n != count) || n == 0) {
      std::ostringstream msg;
      msg << where << " must have " << (count > 0 ? std::to_string(count) : "one or more") << " numbers, has " << n;
      throw std::invalid_argument(msg.str());
    }
  }

  void checkOrigin(const TiXmlElement& parent, const std::string& owner) const {
    if (const TiXmlElement* o = parent.FirstChildElement("origin")) {
      checkNumbers(*o, "xyz", 3, owner, "origin");
      checkNumbers(*o, "rpy", 3, owner, "origin");
    }
  }

  void checkLink(TiXmlElement& link) const {
    const std::string owner = "link " + inQuotes(attribute(link, "name"));
    // Never read: drop them so that nothing in them can fail the load.
    for (const char* unused : {"visual", "inertial"}) {
      while (TiXmlElement* e = link.FirstChildElement(unused)) link.RemoveChild(e);
    }
    int index = 0;
    for (TiXmlElement* c = link.FirstChildElement("collision"); c != nullptr;
         c = c->NextSiblingElement("collision"), ++index) {
      const std::string what = owner + ", collision " + std::to_string(index);
      checkOrigin(*c, what);
      if (const TiXmlElement* g = c->FirstChildElement("geometry")) {
        if (const TiXmlElement* box = g->FirstChildElement("box")) {
          checkNumbers(*box, "size", 3, what, "box");
        }
        if (const TiXmlElement* s = g->FirstChildElement("sphere")) {
          checkNumbers(*s, "radius", 1, what, "sphere");
        }
        if (const TiXmlElement* cyl = g->FirstChildElement("cylinder")) {
          checkNumbers(*cyl, "radius", 1, what, "cylinder");
          checkNumbers(*cyl, "length", 1, what, "cylinder");
        }
        if (const TiXmlElement* mesh = g->FirstChildElement("mesh")) {
          checkNumbers(*mesh, "scale", 3, what, "mesh");
        }
      }
    }
  }

  void checkJoint(const TiXmlElement& joint) const {
    const std::string owner = "joint " + inQuotes(attribute(joint, "name"));
    checkOrigin(joint, owner);
    if (const TiXmlElement* axis = joint.FirstChildElement("axis")) {
      checkNumbers(*axis, "xyz", 3, owner, "axis");
    }
    if (const TiXmlElement* limit = joint.FirstChildElement("limit")) {
      for (const char* attr : {"lower", "upper", "effort", "velocity"}) {
        checkNumbers(*limit, attr, 1, owner, "limit");
      }
    }
    if (const TiXmlElement* mimic = joint.FirstChildElement("mimic")) {
      checkNumbers(*mimic, "multiplier", 1, owner, "mimic");
      checkNumbers(*mimic, "offset", 1, owner, "mimic");
    }
  }

  struct JointLinks {
    std::string joint;
    std::string parent;
  };

  static std::string linkOf(const TiXmlElement& joint, const char* which) {
    const TiXmlElement* e = joint.FirstChildElement(which);
    return e == nullptr ? std::string() : attribute(*e, "link");
  }

  /// urdfdom accepts a link that is the child of two joints, and a joint whose child link is an
  /// ancestor of its parent (itself included): its tree then holds a cycle (of shared pointers,
  /// never freed) and walking it never ends. Both are rejected here, naming the joints.
  void addToTree(const TiXmlElement& joint, std::map<std::string, JointLinks>& parentOf) const {
    const std::string name = attribute(joint, "name");
    const std::string child = linkOf(joint, "child");
    const auto [it, added] = parentOf.emplace(child, JointLinks{name, linkOf(joint, "parent")});
    if (!added) {
      throw std::invalid_argument(context_ + ": link " + inQuotes(child) + " is the child of two joints, " +
                                  inQuotes(it->second.joint) + " and " + inQuotes(name) +
                                  " (URDF kinematics must be a tree)");
    }
  }

  /// Walks up from every child link towards its root. A link met again on the current walk
  /// closes a loop; the walk stops at a link an earlier walk finished, so each link is walked
  /// once and the check is linear in the number of joints.
  void checkNoLoop(const std::map<std::string, JointLinks>& parentOf) const {
    enum class Walk { Current, Finished };
    std::map<std::string, Walk> seen;
    for (const auto& entry : parentOf) {
      std::vector<const std::string*> walked;
      for (const std::string* link = &entry.first;;) {
        const auto s = seen.find(*link);
        if (s != seen.end()) {
          if (s->second == Walk::Current) throwLoop(*link, parentOf.at(*link).joint);
          break;
        }
        const auto up = parentOf.find(*link);
        if (up == parentOf.end()) break;  // a root
        seen.emplace(*link, Walk::Current);
        walked.push_back(link);
        link = &up->second.parent;
      }
      for (const std::string* link : walked) seen[*link] = Walk::Finished;
    }
  }

  [[noreturn]] void throwLoop(const std::string& child, const std::string& joint) const {
    throw std::invalid_argument(context_ + ": joint " + inQuotes(joint) + " closes a loop: its child link " +
                                inQuotes(child) + " is also its parent or an ancestor of it" +
                                " (URDF kinematics must be a tree)");
  }

  std::string context_;
  int maxLinks_;
};

}  // namespace

std::string prepareUrdf(const std::string& xml, const std::string& context, int maxLinks,
                        std::map<std::string, int>& jointOrder, std::set<std::string>& visualLinks) {
  return Prepass(context, maxLinks).run(xml, jointOrder, visualLinks);
}

}  // namespace deepcheck::robots::detail
