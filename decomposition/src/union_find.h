#pragma once
// Internal to deepcheck::decomposition: union-find (disjoint sets) over 0 .. n-1 in a parent array
// (parent[i] == i for a root), with path halving; the smaller index becomes the root, so the
// roots do not depend on the order of the unions.

#include <algorithm>
#include <vector>

namespace deepcheck::decomposition::detail {

/// The root of x's set.
inline int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

/// Joins the sets of a and b.
inline void unite(std::vector<int>& parent, int a, int b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

}  // namespace deepcheck::decomposition::detail
