// Cross-sections of the mesh by a plane (cross_section.h).

#include "cross_section.h"

#include "union_find.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace deepcheck::decomposition::detail {

CrossSection::CrossSection(const CleanMesh& mesh, const Vector3d& normal, double offset, bool withRegions) {
  generalized_ = !mesh.closed;
  const Vector3d helper = std::abs(normal.x()) < 0.6 ? Vector3d::UnitX() : Vector3d::UnitY();
  u_ = normal.cross(helper).normalized();
  v_ = normal.cross(u_);
  std::vector<double> s(mesh.vertices.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = normal.dot(mesh.vertices[i]) - offset;
  std::vector<int> segmentEdges;  // 2 per segment: the mesh edges at its ends
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const auto& tri = mesh.triangles[t];
    const bool up0 = s[tri[0]] >= 0.0;
    const bool up1 = s[tri[1]] >= 0.0;
    const bool up2 = s[tri[2]] >= 0.0;
    if (up0 == up1 && up1 == up2) continue;
    Vector3d ends[2];
    int edges[2] = {-1, -1};
    int found = 0;
    for (int e = 0; e < 3; ++e) {
      int a = tri[e];
      int b = tri[(e + 1) % 3];
      if ((s[a] >= 0.0) == (s[b] >= 0.0)) continue;
      if (a > b) std::swap(a, b);
      if (found < 2) {
        const double t01 = s[a] / (s[a] - s[b]);
        ends[found] = mesh.vertices[a] + t01 * (mesh.vertices[b] - mesh.vertices[a]);
        edges[found] = mesh.edgeOf[3 * t + e];
      }
      ++found;
    }
    if (found != 2) continue;
    const Vector3d& A = mesh.vertices[tri[0]];
    const Vector3d triNormal = (mesh.vertices[tri[1]] - A).cross(mesh.vertices[tri[2]] - A);
    if ((ends[1] - ends[0]).dot(normal.cross(triNormal)) < 0.0) {
      std::swap(ends[0], ends[1]);
      std::swap(edges[0], edges[1]);
    }
    segments_.push_back({u_.dot(ends[0]), v_.dot(ends[0]), u_.dot(ends[1]), v_.dot(ends[1]), t});
    segmentEdges.insert(segmentEdges.end(), {edges[0], edges[1]});
  }
  buildBuckets();
  if (withRegions) buildRegions(segmentEdges);
}

void CrossSection::buildBuckets() {
  if (generalized_ || segments_.empty()) return;
  double vlo = kInf;
  double vhi = -kInf;
  for (const Segment& seg : segments_) {
    vlo = std::min({vlo, seg.av, seg.bv});
    vhi = std::max({vhi, seg.av, seg.bv});
  }
  const int numBuckets = std::clamp(static_cast<int>(segments_.size() / 4), 1, 512);
  vlo_ = vlo;
  width_ = (vhi - vlo) / numBuckets;
  if (!(width_ > 0.0)) width_ = 1.0;
  buckets_.assign(numBuckets, {});
  for (int i = 0; i < static_cast<int>(segments_.size()); ++i) {
    const Segment& seg = segments_[i];
    if (seg.av == seg.bv) continue;  // horizontal: never crosses a horizontal ray
    const int b0 = bucketOf(std::min(seg.av, seg.bv));
    const int b1 = bucketOf(std::max(seg.av, seg.bv));
    for (int b = b0; b <= b1; ++b) buckets_[b].push_back(i);
  }
}

void CrossSection::buildRegions(const std::vector<int>& segmentEdges) {
  const int n = static_cast<int>(segments_.size());
  if (n == 0) return;
  // Loops: segments sharing a crossed mesh edge. (At a non-manifold edge several loops may
  // join: that only merges regions, which is the safe direction.)
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::unordered_map<int, int> firstAtEdge;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 2; ++k) {
      auto [it, inserted] = firstAtEdge.emplace(segmentEdges[2 * i + k], i);
      if (!inserted) unite(parent, i, it->second);
    }
  }
  std::vector<int> loopOf(n);
  std::vector<std::vector<int>> loops;
  std::unordered_map<int, int> loopIndex;
  for (int i = 0; i < n; ++i) {
    auto [it, inserted] = loopIndex.emplace(findRoot(parent, i), static_cast<int>(loops.size()));
    if (inserted) loops.emplace_back();
    loops[it->second].push_back(i);
    loopOf[i] = it->second;
  }
  // Regions: loops that cross each other or lie one inside the other (at any depth, any mesh
  // components) are joined. This is coarser than the true regions of the cut face (a solid rod
  // standing in a tube's hole joins the tube), which only merges more: the safe direction. It
  // needs no consistent orientation, and voids (inward-facing components) join their body.
  const int numLoops = static_cast<int>(loops.size());
  std::vector<int> loopParent(numLoops);
  std::iota(loopParent.begin(), loopParent.end(), 0);
  auto cross = [](double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  };
  auto segmentsMeet = [&](const Segment& p, const Segment& q) {
    const double d1 = cross(p.au, p.av, p.bu, p.bv, q.au, q.av);
    const double d2 = cross(p.au, p.av, p.bu, p.bv, q.bu, q.bv);
    const double d3 = cross(q.au, q.av, q.bu, q.bv, p.au, p.av);
    const double d4 = cross(q.au, q.av, q.bu, q.bv, p.bu, p.bv);
    return ((d1 <= 0.0 && d2 >= 0.0) || (d1 >= 0.0 && d2 <= 0.0)) &&
           ((d3 <= 0.0 && d4 >= 0.0) || (d3 >= 0.0 && d4 <= 0.0));
  };
  std::vector<std::array<double, 4>> boxes(numLoops, {kInf, kInf, -kInf, -kInf});
  for (int a = 0; a < numLoops; ++a) {
    for (int k : loops[a]) {
      const Segment& s = segments_[k];
      boxes[a] = {std::min({boxes[a][0], s.au, s.bu}), std::min({boxes[a][1], s.av, s.bv}),
                  std::max({boxes[a][2], s.au, s.bu}), std::max({boxes[a][3], s.av, s.bv})};
    }
  }
  for (int a = 0; a < numLoops; ++a) {
    for (int b = a + 1; b < numLoops; ++b) {
      if (boxes[a][0] > boxes[b][2] || boxes[b][0] > boxes[a][2] || boxes[a][1] > boxes[b][3] ||
          boxes[b][1] > boxes[a][3]) {
        continue;  // disjoint boxes: neither crossing nor nesting
      }
      const Segment& pa = segments_[loops[a].front()];
      const Segment& pb = segments_[loops[b].front()];
      bool joined = insideLoop(0.5 * (pa.au + pa.bu), 0.5 * (pa.av + pa.bv), loops[b]) ||
                    insideLoop(0.5 * (pb.au + pb.bu), 0.5 * (pb.av + pb.bv), loops[a]);
      for (std::size_t x = 0; !joined && x < loops[a].size(); ++x) {
        for (std::size_t y = 0; !joined && y < loops[b].size(); ++y) {
          joined = segmentsMeet(segments_[loops[a][x]], segments_[loops[b][y]]);
        }
      }
      if (joined) unite(loopParent, a, b);
    }
  }
  std::vector<int> region(numLoops);
  for (int a = 0; a < numLoops; ++a) region[a] = findRoot(loopParent, a);
  loops_ = std::move(loops);
  loopRegion_ = region;
  for (int i = 0; i < n; ++i) regionOfTriangle_[segments_[i].triangle] = region[loopOf[i]];
}

}  // namespace deepcheck::decomposition::detail
