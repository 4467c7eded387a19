// Near matches of an unknown name (near_matches.h).

#include "near_matches.h"

#include "deepcheck/checker/tolerances.h"

#include <algorithm>
#include <utility>

namespace deepcheck::checker::detail {

int editDistance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::vector<std::string> nearMatches(const std::string& name, const std::vector<std::string>& known, int most) {
  std::vector<std::pair<int, std::string>> scored;
  for (const std::string& k : known) {
    const int d = editDistance(name, k);
    const bool contains = !name.empty() && (k.find(name) != std::string::npos || name.find(k) != std::string::npos);
    if (d <= tol::kNearMatchEdits || contains) scored.emplace_back(d, k);
  }
  std::sort(scored.begin(), scored.end());
  scored.erase(std::unique(scored.begin(), scored.end()), scored.end());
  std::vector<std::string> out;
  for (const auto& [d, k] : scored) {
    if (static_cast<int>(out.size()) == most) break;
    out.push_back(k);
  }
  return out;
}

std::string nearMatchesText(const std::string& name, const std::vector<std::string>& known) {
  std::string text;
  for (const std::string& k : nearMatches(name, known)) text += (text.empty() ? "; near matches: '" : ", '") + k + "'";
  return text;
}

}  // namespace deepcheck::checker::detail
