#pragma once
// Which link pairs of a robot are adjacent or rigidly attached, answered per pair and counted,
// without listing the pairs.
//
// Adjacent (robots::adjacentLinkPairs): two links with geometry joined by a joint, or through
// links without geometry only. Rigid (rigidLinkPairs, world.h): two links with geometry in one
// group of links joined by fixed joints. Listing them costs the square of the links for a hub
// without geometry (every pair of its children is adjacent) or a big rigid group; the world only
// asks about the pairs within reach, and counts the rest for its summary.
//
// A URDF's links form a tree (every link has at most one parent joint, and parents precede their
// children in link order). So the links without geometry form subtrees, each named by its top
// link (its "hub"); a link with geometry is adjacent to its parent and children with geometry and
// to every link bordering the hub above it or a hub below it, and two links share at most one hub.

#include "deepcheck/robots/robot_model.h"

#include <vector>

namespace deepcheck::checker {

class LinkPairIndex {
 public:
  /// hasGeometry: one entry per link of `model`.
  LinkPairIndex(const robots::RobotModel& model, const std::vector<bool>& hasGeometry);

  /// Both take two distinct links with geometry.
  bool adjacent(int a, int b) const;
  bool rigid(int a, int b) const { return group_[a] == group_[b]; }

  /// Numbers of adjacent pairs, rigid pairs, and pairs both adjacent and rigid (of links with geometry).
  long long numAdjacent() const { return numAdjacent_; }
  long long numRigid() const { return numRigid_; }
  long long numAdjacentAndRigid() const { return numAdjacentAndRigid_; }

 private:
  /// The hub above link l: the top of the subtree without geometry holding l's parent; -1 when
  /// l's parent has geometry or l is the root.
  int hubAbove(int l) const { return hubAbove_[l]; }

  std::vector<int> parent_;    // parent link, -1 for the root
  std::vector<int> hubAbove_;  // for links with geometry (see hubAbove)
  std::vector<int> group_;     // rigid group: the topmost link reached through fixed joints
  long long numAdjacent_ = 0;
  long long numRigid_ = 0;
  long long numAdjacentAndRigid_ = 0;
};

}  // namespace deepcheck::checker
