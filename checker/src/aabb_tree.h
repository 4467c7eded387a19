#pragma once
// A static AABB tree over axis-aligned bounding boxes (Aabb, deepcheck/checker/broad_phase.h): the
// World's own broad phase.
//
// The tree is a binary bounding-volume hierarchy built once, top down: a node's items are split
// at the median of their box centres along the longest axis of the centres' extent, until at
// most kLeafSize items remain. Nodes are stored in one array, depth first (a node's left child
// follows it), so a traversal walks memory forwards. Queries never allocate.
//
// Why not FCL's DynamicAABBTreeCollisionManager: the scene never changes between queries, and a
// static tree of plain boxes answers "which items are near this sphere" without virtual calls or
// collision objects; WorldOptions::externalBroadPhase takes FCL's tree instead
// (deepcheck::fcl_reference::fclBroadPhase()), and bench/checker_bench.cpp measures both.
//
// Frames: all boxes are in the world frame W. Metres.

#include "deepcheck/checker/broad_phase.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace deepcheck::checker {

class AabbTree {
 public:
  static constexpr int kLeafSize = 2;

  AabbTree() = default;
  /// Builds the tree over items 0 .. boxes.size() - 1.
  explicit AabbTree(const std::vector<Aabb>& boxes);

  int size() const { return static_cast<int>(items_.size()); }
  int numNodes() const { return static_cast<int>(nodes_.size()); }
  bool empty() const { return items_.empty(); }

  /// Calls visit(item) for every item whose box overlaps `query`, until visit returns true (stop).
  /// Returns true when it was stopped.
  template <class Visit>
  bool visitOverlapping(const Aabb& query, Visit&& visit) const;

  /// Branch and bound around a sphere (centre c, radius r): calls visit(item, lowerBound) for the
  /// items whose box is within bound() of the sphere (lowerBound = the item box's signed distance
  /// from c minus r, Aabb::signedDistance: a lower bound on the signed distance of anything in the
  /// sphere to anything in the box, however deep), nearer subtrees first. bound() is read again before every node, so
  /// visit may tighten it (a best-so-far distance).
  template <class Bound, class Visit>
  void visitNear(const Eigen::Vector3d& c, double r, Bound&& bound, Visit&& visit) const;

 private:
  struct Node {
    Aabb box;
    int first = 0;  ///< leaf: first index into items_; inner: index of the right child
    int count = 0;  ///< leaf: number of items (> 0); inner: 0 (the left child is this + 1)
  };
  int build(std::vector<int>& order, const std::vector<Aabb>& boxes, const std::vector<Eigen::Vector3d>& centers,
            int begin, int end);

  std::vector<Node> nodes_;
  std::vector<int> items_;
  std::vector<Aabb> itemBoxes_;  // itemBoxes_[i] is the box of items_[i]
  static constexpr int kMaxDepth = 64;
};

template <class Visit>
bool AabbTree::visitOverlapping(const Aabb& query, Visit&& visit) const {
  if (nodes_.empty()) return false;
  int stack[kMaxDepth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.overlaps(query)) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (itemBoxes_[i].overlaps(query) && visit(items_[i])) return true;
      }
    } else {
      const int self = static_cast<int>(&node - nodes_.data());
      stack[top++] = node.first;
      stack[top++] = self + 1;
    }
  }
  return false;
}

template <class Bound, class Visit>
void AabbTree::visitNear(const Eigen::Vector3d& c, double r, Bound&& bound, Visit&& visit) const {
  if (nodes_.empty()) return;
  struct Entry {
    int node;
    double lowerBound;
  };
  Entry stack[kMaxDepth];
  int top = 0;
  stack[top++] = {0, nodes_[0].box.signedDistance(c) - r};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.lowerBound >= bound()) continue;
    const Node& node = nodes_[e.node];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const double lowerBound = itemBoxes_[i].signedDistance(c) - r;
        if (lowerBound < bound()) visit(items_[i], lowerBound);
      }
      continue;
    }
    const int left = e.node + 1;
    const int right = node.first;
    const double dl = nodes_[left].box.signedDistance(c) - r;
    const double dr = nodes_[right].box.signedDistance(c) - r;
    // Push the farther child first so the nearer one is visited first.
    if (dl <= dr) {
      stack[top++] = {right, dr};
      stack[top++] = {left, dl};
    } else {
      stack[top++] = {left, dl};
      stack[top++] = {right, dr};
    }
  }
}

}  // namespace deepcheck::checker
