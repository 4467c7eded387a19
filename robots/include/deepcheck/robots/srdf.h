#pragma once
// Disabled collision pairs, virtual joints and the SRDF files that hold them (MoveIt's format).
//
// SRDF: <robot name="..."> with one <disable_collisions link1="A" link2="B" reason="R"/> per pair
// and <virtual_joint name="J" type="fixed|floating|planar" parent_frame="F" child_link="L"/> for
// the joint that places the robot's root link L in the frame F (MoveIt's model frame, e.g. world
// or odom_combined); planning groups are read by planning_group.h. Other SRDF elements (group
// states, end effectors, passive joints) are ignored when reading and not written. A missing reason attribute is
// DisableReason::Unspecified (example-robot-data's ur5.srdf has none); reason "User" (MoveIt's hand-made pairs) is
// DisableReason::User; any other text (MoveIt accepts any, e.g. "Common") is DisableReason::Other with the text kept in
// DisabledPair::reasonText, so that it is shown and written back as found.
//
// Errors: bad input throws std::invalid_argument whose message names the file (or the text's
// source), the line and the offending value; elements nested deeper than kMaxNestingDepth
// (robot_model.h) are rejected before the text is parsed.

#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"

#include <string>
#include <utility>
#include <vector>

namespace deepcheck::robots {

enum class DisableReason {
  Adjacent,     ///< joined by a joint (possibly through links without geometry)
  Default,      ///< in collision at the default configuration
  Always,       ///< in collision in at least alwaysFraction of the random samples
  Never,        ///< in collision in none of the random samples
  User,         ///< disabled by hand (SRDF reason "User"); never computed here
  Unspecified,  ///< SRDF entry without a reason attribute; never computed here
  Other,        ///< SRDF reason text other than the five words above; never computed here
};
constexpr int kNumDisableReasons = 7;

/// The SRDF word: "Adjacent", "Default", "Always", "Never", "User"; "" for Unspecified; "Other"
/// for Other (whose own text is DisabledPair::reasonText).
const char* toString(DisableReason reason);
/// Inverse of toString() for the five words (case-sensitive, as MoveIt writes them); "" gives
/// Unspecified; any other text gives Other.
DisableReason parseDisableReason(const std::string& text);

/// One disabled pair, by link name. Pairs are unordered: (A, B) and (B, A) are the same pair.
struct DisabledPair {
  DisabledPair() = default;
  DisabledPair(std::string link1, std::string link2, DisableReason reason = DisableReason::Unspecified,
               std::string reasonText = "")
      : link1(std::move(link1)), link2(std::move(link2)), reason(reason), reasonText(std::move(reasonText)) {}

  std::string link1;
  std::string link2;
  DisableReason reason = DisableReason::Unspecified;
  /// The SRDF reason text when `reason` is Other (e.g. "Common"); empty otherwise.
  std::string reasonText;
};

/// The reason as an SRDF would write it: `reasonText` for Other, else toString(reason).
std::string reasonText(const DisabledPair& pair);

/// (min, max) of the two names: a key under which (A, B) and (B, A) are equal.
std::pair<std::string, std::string> pairKey(const std::string& a, const std::string& b);

/// The <disable_collisions> entries of SRDF text, in file order. `sourceName` names the text in
/// messages. Throws std::invalid_argument (naming the source and the line) for malformed XML, a
/// root element other than <robot>, or a missing or empty link1/link2.
std::vector<DisabledPair> parseSrdfDisabledPairs(const std::string& xml, const std::string& sourceName = "");
/// Same, from a file (a missing or unreadable file is an error naming it).
std::vector<DisabledPair> readSrdfDisabledPairs(const std::string& path);

/// One <virtual_joint> of an SRDF.
struct SrdfVirtualJoint {
  std::string name;
  std::string type;         ///< "fixed", "floating" or "planar"
  std::string parentFrame;  ///< the frame the robot is placed in (MoveIt's model frame)
  std::string childLink;    ///< the robot's root link
  int line = 0;             ///< of the element, 1-based
};

/// The <virtual_joint> elements of SRDF text, in file order. Throws std::invalid_argument naming
/// the source and the line for malformed XML, a root other than <robot>, a missing or empty
/// attribute, or a type other than fixed, floating and planar.
std::vector<SrdfVirtualJoint> parseSrdfVirtualJoints(const std::string& xml, const std::string& sourceName = "");
/// Same, from a file.
std::vector<SrdfVirtualJoint> readSrdfVirtualJoints(const std::string& path);

/// What srdfText writes, in MoveIt's order: groups, virtual joints, disabled pairs.
struct SrdfContents {
  std::vector<SrdfGroup> groups;  ///< each with its joints, links, chains, then subgroups
  std::vector<SrdfVirtualJoint> virtualJoints;
  std::vector<DisabledPair> pairs;
};

/// The name of the group defaultChainGroup makes.
inline const std::string kDefaultGroupName = "manipulator";

/// A planning group for a robot whose SRDF gives none: group kDefaultGroupName holding one chain
/// from the root link to the tip, the link at the end of the robot's longest chain of moving
/// joints: of the leaf links with the most moving joints above them, the deepest link that all of
/// them hang from (for an arm with a hand and two fixed fingers: the hand, not a finger), or the
/// first of them when they branch apart above a moving joint (two arms). Throws
/// std::invalid_argument naming the robot when it has no moving joint.
SrdfGroup defaultChainGroup(const RobotModel& robot);

/// SRDF text: an XML declaration, `comment` (if not empty) as an XML comment, and
/// <robot name="robotName"> with one <disable_collisions> per pair in the given order (reason
/// omitted for Unspecified, reasonText(pair) otherwise). Names and reasons are XML-escaped.
std::string srdfText(const std::string& robotName, const std::vector<DisabledPair>& pairs,
                     const std::string& comment = "");
/// SRDF text as above with `contents`: each group as <group name> holding <joint name>, <link
/// name>, <chain base_link tip_link> and <group name> elements (in that order: parseSrdfGroups
/// reads them back to the same SrdfGroup), then the <virtual_joint> elements, then the pairs.
std::string srdfText(const std::string& robotName, const SrdfContents& contents, const std::string& comment = "");
/// Writes srdfText() to `path`; throws std::invalid_argument naming the file when it cannot.
void writeSrdf(const std::string& path, const std::string& robotName, const std::vector<DisabledPair>& pairs,
               const std::string& comment = "");
/// Same, with groups and virtual joints.
void writeSrdf(const std::string& path, const std::string& robotName, const SrdfContents& contents,
               const std::string& comment = "");

}  // namespace deepcheck::robots
