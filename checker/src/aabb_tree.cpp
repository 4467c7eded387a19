#include "aabb_tree.h"

#include <numeric>

namespace deepcheck::checker {

AabbTree::AabbTree(const std::vector<Aabb>& boxes) {
  if (boxes.empty()) return;
  std::vector<Eigen::Vector3d> centers;
  centers.reserve(boxes.size());
  for (const Aabb& b : boxes) centers.push_back(b.center());
  std::vector<int> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  nodes_.reserve(2 * boxes.size());
  build(order, boxes, centers, 0, static_cast<int>(order.size()));
  items_ = std::move(order);
  itemBoxes_.reserve(items_.size());
  for (int item : items_) itemBoxes_.push_back(boxes[item]);
}

int AabbTree::build(std::vector<int>& order, const std::vector<Aabb>& boxes,
                    const std::vector<Eigen::Vector3d>& centers, int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Aabb box;
  Aabb centerBox;
  for (int i = begin; i < end; ++i) {
    box.extend(boxes[order[i]]);
    centerBox.extend(centers[order[i]]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  (centerBox.hi - centerBox.lo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](int a, int b) { return centers[a][axis] < centers[b][axis]; });
  build(order, boxes, centers, begin, mid);  // left child: index + 1
  const int right = build(order, boxes, centers, mid, end);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

}  // namespace deepcheck::checker
