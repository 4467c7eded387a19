#pragma once
// Disabled collision pairs and the SRDF files that hold them (MoveIt's format).
//
// SRDF: <robot name="..."> with one <disable_collisions link1="A" link2="B" reason="R"/> per pair.
// Other SRDF elements (groups, states, virtual joints, end effectors) are ignored when reading and
// not written. A missing reason attribute is DisableReason::Unspecified (example-robot-data's
// ur5.srdf has none); reason "User" (MoveIt's hand-made pairs) is DisableReason::User; any other
// reason is an error.
//
// Errors: bad input throws std::invalid_argument whose message names the file (or the text's
// source), the line and the offending value; elements nested deeper than kMaxNestingDepth
// (robot_model.h) are rejected before the text is parsed.

#include <optional>
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
};
constexpr int kNumDisableReasons = 6;

/// The SRDF word: "Adjacent", "Default", "Always", "Never", "User"; "" for Unspecified.
const char* toString(DisableReason reason);
/// Inverse of toString() for the five words (case-sensitive, as MoveIt writes them); "" gives
/// Unspecified; any other text gives std::nullopt.
std::optional<DisableReason> parseDisableReason(const std::string& text);

/// One disabled pair, by link name. Pairs are unordered: (A, B) and (B, A) are the same pair.
struct DisabledPair {
  std::string link1;
  std::string link2;
  DisableReason reason = DisableReason::Unspecified;
};

/// (min, max) of the two names: a key under which (A, B) and (B, A) are equal.
std::pair<std::string, std::string> pairKey(const std::string& a, const std::string& b);

/// The <disable_collisions> entries of SRDF text, in file order. `sourceName` names the text in
/// messages. Throws std::invalid_argument (naming the source and the line) for malformed XML, a
/// root element other than <robot>, a missing or empty link1/link2, or an unknown reason.
std::vector<DisabledPair> parseSrdfDisabledPairs(const std::string& xml,
                                                 const std::string& sourceName = "");
/// Same, from a file (a missing or unreadable file is an error naming it).
std::vector<DisabledPair> readSrdfDisabledPairs(const std::string& path);

/// SRDF text: an XML declaration, `comment` (if not empty) as an XML comment, and
/// <robot name="robotName"> with one <disable_collisions> per pair in the given order (reason
/// omitted for Unspecified). Names are XML-escaped.
std::string srdfText(const std::string& robotName, const std::vector<DisabledPair>& pairs,
                     const std::string& comment = "");
/// Writes srdfText() to `path`; throws std::invalid_argument naming the file when it cannot.
void writeSrdf(const std::string& path, const std::string& robotName,
               const std::vector<DisabledPair>& pairs, const std::string& comment = "");

}  // namespace deepcheck::robots
