#include "link_pairs.h"

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace deepcheck::checker {

namespace {

long long pairsOf(long long k) { return k * (k - 1) / 2; }

}  // namespace

LinkPairIndex::LinkPairIndex(const robots::RobotModel& model, const std::vector<bool>& hasGeometry) {
  const int n = model.numLinks();
  if (static_cast<int>(hasGeometry.size()) != n) {
    throw std::invalid_argument("LinkPairIndex: robot '" + model.name() + "' has " + std::to_string(n) +
                                " links, hasGeometry has " + std::to_string(hasGeometry.size()) + " entries");
  }
  parent_.assign(n, -1);
  hubAbove_.assign(n, -1);
  group_.assign(n, 0);
  std::vector<int> hubOf(n, -1);  // for links without geometry: the top of their subtree
  for (int l = 0; l < n; ++l) {   // parents precede children
    const robots::Link& link = model.link(l);
    const int p = link.parentLink;
    parent_[l] = p;
    group_[l] = (link.parentJoint >= 0 && !model.joint(link.parentJoint).moves()) ? group_[p] : l;
    if (!hasGeometry[l]) hubOf[l] = (p >= 0 && !hasGeometry[p]) ? hubOf[p] : l;
    if (hasGeometry[l] && p >= 0 && !hasGeometry[p]) hubAbove_[l] = hubOf[p];
  }
  // Each hub's members: the links with geometry below it, and the link with geometry above it.
  // Each pair of members is adjacent; so is each joint between two links with geometry.
  std::unordered_map<int, std::vector<int>> members;
  std::unordered_map<int, long long> rigidSize;
  for (int l = 0; l < n; ++l) {
    if (!hasGeometry[l]) continue;
    ++rigidSize[group_[l]];
    if (hubAbove_[l] >= 0) members[hubAbove_[l]].push_back(l);
    const int p = parent_[l];
    if (p >= 0 && hasGeometry[p]) {
      ++numAdjacent_;
      numAdjacentAndRigid_ += group_[p] == group_[l];
    }
  }
  for (auto& [hub, links] : members) {
    if (parent_[hub] >= 0) links.push_back(parent_[hub]);  // the hub's parent has geometry
    numAdjacent_ += pairsOf(static_cast<long long>(links.size()));
    std::unordered_map<int, long long> byGroup;
    for (int l : links) ++byGroup[group_[l]];
    for (const auto& [group, k] : byGroup) numAdjacentAndRigid_ += pairsOf(k);
  }
  for (const auto& [group, k] : rigidSize) numRigid_ += pairsOf(k);
}

bool LinkPairIndex::adjacent(int a, int b) const {
  if (parent_[a] == b || parent_[b] == a) return true;  // joined by a joint
  const int ha = hubAbove_[a];
  const int hb = hubAbove_[b];
  // Through links without geometry: below one hub, or one below a hub whose parent is the other.
  return (ha >= 0 && (ha == hb || parent_[ha] == b)) || (hb >= 0 && parent_[hb] == a);
}

}  // namespace deepcheck::checker
