#include "deepcheck/robots/planning_group.h"

#include "xml_text.h"
#include "in_quotes.h"

#include <tinyxml.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <unordered_map>

namespace deepcheck::robots {

using detail::inQuotes;

namespace {

std::string srdfContext(const std::string& source) { return "SRDF " + inQuotes(source.empty() ? "<string>" : source); }

/// The value of `attr`; throws naming `where` and `element` when it is absent or empty.
std::string requiredAttribute(const TiXmlElement* e, const char* attr, const std::string& where,
                              const std::string& element) {
  const char* value = e->Attribute(attr);
  if (value == nullptr || *value == '\0') {
    throw std::invalid_argument(where + ": " + element + " without " + attr);
  }
  return value;
}

/// One <group> element and what it holds.
SrdfGroup parseGroup(const TiXmlElement* g, const std::string& context) {
  SrdfGroup group;
  group.line = g->Row();
  group.name = requiredAttribute(g, "name", context + ", line " + std::to_string(g->Row()), "<group>");
  for (const TiXmlElement* e = g->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string tag = e->Value();
    const std::string where = context + ", line " + std::to_string(e->Row()) + ", group " + inQuotes(group.name);
    if (tag == "joint") {
      group.joints.push_back(requiredAttribute(e, "name", where, "<joint>"));
    } else if (tag == "link") {
      group.links.push_back(requiredAttribute(e, "name", where, "<link>"));
    } else if (tag == "chain") {
      std::string base = requiredAttribute(e, "base_link", where, "<chain>");
      std::string tip = requiredAttribute(e, "tip_link", where, "<chain>");
      group.chains.emplace_back(std::move(base), std::move(tip));
    } else if (tag == "group") {
      group.subgroups.push_back(requiredAttribute(e, "name", where, "<group>"));
    } else if (tag != "passive_joint") {
      throw std::invalid_argument(where + ": unexpected element <" + tag +
                                  "> (a group holds joint, link, chain, group and passive_joint "
                                  "elements)");
    }
  }
  return group;
}

}  // namespace

std::vector<SrdfGroup> parseSrdfGroups(const std::string& xml, const std::string& sourceName) {
  const std::string context = srdfContext(sourceName);
  TiXmlDocument doc;
  const TiXmlElement& robot = parseSrdfRoot(doc, xml, context);
  std::vector<SrdfGroup> groups;
  std::unordered_map<std::string, int> lineOf;
  for (const TiXmlElement* g = robot.FirstChildElement("group"); g != nullptr; g = g->NextSiblingElement("group")) {
    SrdfGroup group = parseGroup(g, context);
    const auto [earlier, isNew] = lineOf.emplace(group.name, group.line);
    if (!isNew) {
      throw std::invalid_argument(context + ", line " + std::to_string(group.line) + ": group " + inQuotes(group.name) +
                                  " is defined twice (first at line " + std::to_string(earlier->second) + ")");
    }
    groups.push_back(std::move(group));
  }
  return groups;
}

std::vector<SrdfGroup> readSrdfGroups(const std::string& path) { return parseSrdfGroups(readSrdfText(path), path); }

namespace {

/// Collects the joints of a group and of its subgroups, depth first with an explicit stack (a
/// file may nest subgroups deeper than the call stack could), detecting cycles.
class GroupResolver {
 public:
  GroupResolver(const RobotModel& model, const std::vector<SrdfGroup>& groups, const std::string& srdfSource)
      : model_(model),
        groups_(groups),
        context_(srdfContext(srdfSource)),
        state_(groups.size(), State::Unvisited),
        inGroup_(model.numJoints(), false) {
    for (std::size_t g = 0; g < groups.size(); ++g) {
      index_.emplace(groups[g].name, static_cast<int>(g));
    }
  }

  /// Index of the group called `name` in `groups` (the first one), -1 when there is none.
  int find(const std::string& name) const {
    const auto it = index_.find(name);
    return it == index_.end() ? -1 : it->second;
  }

  /// Adds the joints of group g and of its subgroups, recursively.
  void add(int g) {
    enter(g);
    while (!path_.empty()) {
      const SrdfGroup& group = groups_[path_.back().group];
      std::size_t& next = path_.back().nextSubgroup;
      if (next == group.subgroups.size()) {
        state_[path_.back().group] = State::Done;
        path_.pop_back();
        continue;
      }
      const std::string& name = group.subgroups[next++];
      const int s = find(name);
      if (s < 0) {
        throw std::invalid_argument(where(group) + ": subgroup " + inQuotes(name) + " is not a group of the file");
      }
      if (state_[s] == State::InProgress) throwCycle(group, s);
      if (state_[s] == State::Unvisited) enter(s);
    }
  }

  /// The variables of the collected joints, ascending; throws naming group g when there are none.
  std::vector<int> variables(int g) const {
    std::vector<int> result;
    std::string joints;
    for (int j = 0; j < model_.numJoints(); ++j) {
      if (!inGroup_[j]) continue;
      const Joint& joint = model_.joint(j);
      if (joint.moves() && !joint.isMimic()) result.push_back(joint.variable);
      joints += (joints.empty() ? "" : ", ") + joint.name;
    }
    if (result.empty()) {
      throw std::invalid_argument(where(groups_[g]) + ": the group moves no variable of " + robot() +
                                  (joints.empty() ? std::string(": it has no joint")
                                                  : ": its joints " + joints + " are fixed or mimic joints"));
    }
    std::sort(result.begin(), result.end());
    return result;
  }

 private:
  enum class State { Unvisited, InProgress, Done };
  struct Visit {
    int group;
    std::size_t nextSubgroup;  ///< the subgroup to visit next
  };

  /// Marks group g in progress and adds its own joints, links and chains.
  void enter(int g) {
    const SrdfGroup& group = groups_[g];
    state_[g] = State::InProgress;
    path_.push_back({g, 0});
    for (const std::string& joint : group.joints) addJoint(group, joint);
    for (const std::string& link : group.links) {
      const int parent = model_.link(linkIndex(group, link)).parentJoint;
      if (parent >= 0) inGroup_[parent] = true;
    }
    for (const auto& [base, tip] : group.chains) addChain(group, base, tip);
  }

  std::string where(const SrdfGroup& group) const {
    return context_ + ", line " + std::to_string(group.line) + ", group " + inQuotes(group.name);
  }
  std::string robot() const { return "robot " + inQuotes(model_.name()) + " (" + model_.source() + ")"; }

  void addJoint(const SrdfGroup& group, const std::string& name) {
    const int j = model_.jointIndex(name);
    if (j < 0) {
      throw std::invalid_argument(where(group) + ": joint " + inQuotes(name) + " is not in " + robot());
    }
    inGroup_[j] = true;
  }

  int linkIndex(const SrdfGroup& group, const std::string& name) const {
    const int l = model_.linkIndex(name);
    if (l < 0) {
      throw std::invalid_argument(where(group) + ": link " + inQuotes(name) + " is not in " + robot());
    }
    return l;
  }

  /// The parent joints of the links from tip up to base, base excluded.
  void addChain(const SrdfGroup& group, const std::string& base, const std::string& tip) {
    const int b = linkIndex(group, base);
    std::vector<int> joints;
    int l = linkIndex(group, tip);
    for (; l >= 0 && l != b; l = model_.link(l).parentLink) {
      joints.push_back(model_.link(l).parentJoint);
    }
    if (l != b) {
      throw std::invalid_argument(where(group) + ": <chain base_link=" + inQuotes(base) + " tip_link=" + inQuotes(tip) +
                                  ">: " + inQuotes(base) + " is not an ancestor of " + inQuotes(tip) + " in " +
                                  robot());
    }
    for (int j : joints) inGroup_[j] = true;
  }

  [[noreturn]] void throwCycle(const SrdfGroup& group, int s) const {
    std::string cycle;
    std::size_t k = 0;
    while (path_[k].group != s) ++k;
    for (; k < path_.size(); ++k) cycle += groups_[path_[k].group].name + " -> ";
    throw std::invalid_argument(where(group) + ": subgroups form a cycle: " + cycle + groups_[s].name);
  }

  const RobotModel& model_;
  const std::vector<SrdfGroup>& groups_;
  std::string context_;
  std::vector<State> state_;
  std::unordered_map<std::string, int> index_;  ///< group name -> first group of that name
  std::vector<Visit> path_;                     ///< the groups being added, outermost first
  std::vector<bool> inGroup_;
};

}  // namespace

std::vector<int> groupVariables(const RobotModel& model, const std::vector<SrdfGroup>& groups, const std::string& name,
                                const std::string& srdfSource) {
  GroupResolver resolver(model, groups, srdfSource);
  const int g = resolver.find(name);
  if (g < 0) {
    std::string defined;
    for (const SrdfGroup& group : groups) {
      defined += (defined.empty() ? "" : ", ") + inQuotes(group.name);
    }
    throw std::invalid_argument(
        srdfContext(srdfSource) + ": no group " + inQuotes(name) +
        (defined.empty() ? " (the file defines no group)" : " (the file defines " + defined + ")"));
  }
  resolver.add(g);
  return resolver.variables(g);
}

namespace {

bool sameGroup(const SrdfGroup& a, const SrdfGroup& b) {
  return a.joints == b.joints && a.links == b.links && a.chains == b.chains && a.subgroups == b.subgroups;
}

}  // namespace

std::vector<SrdfGroup> readSrdfGroups(const std::vector<std::string>& paths) {
  std::vector<SrdfGroup> merged;
  std::vector<std::string> sourceOf;  // the file of each group of `merged`
  for (const std::string& path : paths) {
    for (SrdfGroup& group : readSrdfGroups(path)) {
      const auto same =
          std::find_if(merged.begin(), merged.end(), [&](const SrdfGroup& g) { return g.name == group.name; });
      if (same == merged.end()) {
        merged.push_back(std::move(group));
        sourceOf.push_back(path);
        continue;
      }
      if (sameGroup(*same, group)) continue;
      const std::string& first = sourceOf[static_cast<std::size_t>(same - merged.begin())];
      throw std::invalid_argument(srdfContext(path) + ", line " + std::to_string(group.line) + ": group " +
                                  inQuotes(group.name) + " is defined differently in " + srdfContext(first) +
                                  ", line " + std::to_string(same->line));
    }
  }
  return merged;
}

std::string srdfSourceName(const std::vector<std::string>& paths) {
  std::string joined;
  for (const std::string& path : paths) joined += (joined.empty() ? "" : ", ") + path;
  return joined;
}

RobotModel planningGroupModel(const RobotModel& model, const std::string& srdfPath, const std::string& group,
                              const std::map<std::string, double>& locked) {
  return planningGroupModel(model, srdfPath.empty() ? std::vector<std::string>{} : std::vector<std::string>{srdfPath},
                            group, locked);
}

RobotModel planningGroupModel(const RobotModel& model, const std::vector<std::string>& srdfPaths,
                              const std::string& group, const std::map<std::string, double>& locked) {
  if (group.empty()) return model.withLockedVariables(locked);
  if (srdfPaths.empty()) {
    throw std::invalid_argument("robot '" + model.name() + "': planning group '" + group +
                                "' asked for without an SRDF (the groups are the SRDF's)");
  }
  const std::string source = srdfSourceName(srdfPaths);
  const std::vector<int> moved = groupVariables(model, readSrdfGroups(srdfPaths), group, source);
  return lockAllBut(model, moved, locked, "group '" + group + "' of SRDF '" + source + "'");
}

}  // namespace deepcheck::robots
