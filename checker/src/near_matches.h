#pragma once
// Near matches of an unknown name, for error messages ("no body named 'tabel'; near matches:
// 'table'").

#include <string>
#include <vector>

namespace deepcheck::checker::detail {

/// Levenshtein distance (insertions, deletions, substitutions of single bytes).
int editDistance(const std::string& a, const std::string& b);

/// The `known` names within tol::kNearMatchEdits edits of `name` or containing it (or contained
/// in it), nearest first, at most `most`; duplicates removed.
std::vector<std::string> nearMatches(const std::string& name, const std::vector<std::string>& known, int most = 5);

/// "; near matches: 'a', 'b'" or "" when there is none.
std::string nearMatchesText(const std::string& name, const std::vector<std::string>& known);

}  // namespace deepcheck::checker::detail
