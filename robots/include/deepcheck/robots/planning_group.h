#pragma once
// Planning groups: MoveIt's SRDF <group> elements, read from the file and resolved to the
// variables of a robot's configuration q that each group moves.
//
// SRDF: inside <robot>, each <group name="G"> holds any number of
//   <joint name="J"/>                       joint J;
//   <link name="L"/>                        the parent joint of link L (none for the root link);
//   <chain base_link="B" tip_link="T"/>     the joints from B down to T: the parent joints of the
//                                           links on that path below B, T's included, B's not
//                                           (this is what MoveIt builds, although the comment
//                                           MoveIt writes into SRDF files says B's parent joint
//                                           is included too);
//   <group name="S"/>                       the joints of group S, recursively;
//   <passive_joint name="J"/>               read and ignored: not a joint of the group.
// A group's joints are the union of these. Its variables are those of its joints that move and
// are not mimic joints (a mimic joint follows the variable it mimics, which the group moves only
// if it holds that joint too). Other elements of the SRDF (states, end effectors, disabled
// pairs) are ignored here.
//
// Errors: bad input throws std::invalid_argument whose message starts with "SRDF '<file>'" and
// names the line, the group and the offending value: malformed XML, a root element other than
// <robot>, a group without a name or defined twice, an element of a group without its name (or a
// chain without base_link or tip_link), an element a group cannot hold; and, when resolving, an
// unknown group (the message lists the groups the file defines), a joint or link the robot lacks,
// a chain whose base_link is not tip_link or an ancestor of it, an unknown subgroup, subgroups
// that contain each other, and a group that moves no variable.

#include "deepcheck/robots/robot_model.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::robots {

/// One <group> of an SRDF, as written (names not checked against any robot).
struct SrdfGroup {
  std::string name;
  int line = 0;                                             ///< of the <group> element
  std::vector<std::string> joints;                          ///< <joint name=".."/>
  std::vector<std::string> links;                           ///< <link name=".."/>
  std::vector<std::pair<std::string, std::string>> chains;  ///< <chain base_link tip_link/>
  std::vector<std::string> subgroups;                       ///< <group name=".."/> inside
};

/// The <group> elements of SRDF text, in file order, each element list in file order.
/// `sourceName` names the text in messages ("<string>" when empty).
std::vector<SrdfGroup> parseSrdfGroups(const std::string& xml, const std::string& sourceName = "");
/// parseSrdfGroups() of a file; the path names it in messages.
std::vector<SrdfGroup> readSrdfGroups(const std::string& path);
/// The groups of several SRDF files, in file order: a robot's groups and its disabled pairs may
/// come in separate files (the PR2's do). A group that several files define alike (same joints,
/// links, chains and subgroups, in the same order) is kept once; a group two files define
/// differently is an error naming both files, their lines and the group.
std::vector<SrdfGroup> readSrdfGroups(const std::vector<std::string>& paths);
/// The SRDF files as one source for messages: their paths joined by ", ".
std::string srdfSourceName(const std::vector<std::string>& paths);

/// The variables (indices into the model's configuration q, ascending, no duplicates) that the
/// group `name` of `groups` moves. `srdfSource` names the SRDF in messages.
std::vector<int> groupVariables(const RobotModel& model, const std::vector<SrdfGroup>& groups, const std::string& name,
                                const std::string& srdfSource);

/// The model a planner of group `group` of the SRDF at `srdfPath` sees: lockAllBut(model,
/// groupVariables(...), locked, ...) (robot_model.h), every variable outside the group held at its
/// `locked` value (variable name -> rad or m), else at its default. With no group (""), `model`
/// with `locked` held (withLockedVariables). Throws std::invalid_argument for a group without an
/// SRDF, and what readSrdfGroups, groupVariables and lockAllBut throw.
RobotModel planningGroupModel(const RobotModel& model, const std::string& srdfPath, const std::string& group,
                              const std::map<std::string, double>& locked);
/// Same, with the groups of several SRDF files (readSrdfGroups(paths)); no files is no SRDF.
RobotModel planningGroupModel(const RobotModel& model, const std::vector<std::string>& srdfPaths,
                              const std::string& group, const std::map<std::string, double>& locked);

}  // namespace deepcheck::robots
