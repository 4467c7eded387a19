#pragma once
// Internal to deepcheck::decomposition: the cross-section of the whole mesh by a plane
// (cross_section.cpp).
//
// Cross-section of the whole mesh by a plane: "is this point of the plane inside the solid", and
// which pieces of the mesh surface are joined through the solid's cut face there.
//
// Each triangle crossing the plane gives one segment, oriented along n x (triangle normal): for a
// closed outward-facing mesh (cleanMesh orients every closed component outward) the section's
// loops then run counter-clockwise about n around solid regions, and the winding number is +1
// inside (overlapping components add up). A vertex on the plane counts as above it (symbolic
// perturbation), so every edge is crossed consistently and the loops close even when the plane
// passes through vertices. Crossing points are computed from the edge's lower-index end, so the
// two triangles of an edge produce the same point.
//
// Closed meshes: crossing-number winding, with segments bucketed along the second plane axis so
// that a query scans one bucket. Open meshes: the generalized winding number (the signed angle the
// segments subtend, over 2 pi, inside when >= 1/2), which degrades gracefully at holes.
//
// Regions (only for the planes of accepted cuts): segments chain into loops through the mesh
// edges they cross; loops that cross or nest are joined into one region. The cut face of the
// solid is a union of regions, and two surface pieces bordering the same region may be connected
// through the solid (see components()).

#include "basics.h"
#include "clean_mesh.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace deepcheck::decomposition::detail {

class CrossSection {
 public:
  CrossSection(const CleanMesh& mesh, const Vector3d& normal, double offset, bool withRegions);

  /// True when p (a point on the plane) is inside the solid's cross-section.
  bool contains(const Vector3d& p) const {
    if (segments_.empty()) return false;
    const double pu = u_.dot(p);
    const double pv = v_.dot(p);
    return windingAt(pu, pv);
  }

  /// Region of the cut face bordered by the segment of mesh triangle `triangle` (-1: none).
  int regionOfTriangle(int triangle) const {
    const auto it = regionOfTriangle_.find(triangle);
    return it == regionOfTriangle_.end() ? -1 : it->second;
  }

  /// Region with a loop enclosing p, a point on the plane (-1: none). Enclosing loops nest, so
  /// they all belong to one region.
  int regionAt(const Vector3d& p) const {
    const double pu = u_.dot(p);
    const double pv = v_.dot(p);
    for (std::size_t l = 0; l < loops_.size(); ++l) {
      if (insideLoop(pu, pv, loops_[l])) return loopRegion_[l];
    }
    return -1;
  }

 private:
  struct Segment {
    double au, av, bu, bv;
    int triangle;
  };

  bool insideLoop(double pu, double pv, const std::vector<int>& loop) const {
    bool inside = false;
    for (int k : loop) {
      const Segment& s = segments_[k];
      if ((s.av > pv) != (s.bv > pv)) {
        const double u = s.au + (pv - s.av) / (s.bv - s.av) * (s.bu - s.au);
        if (u > pu) inside = !inside;
      }
    }
    return inside;
  }

  int bucketOf(double v) const {
    // Clamped before the cast: a point far off the section (or NaN) has no int bucket index.
    const double last = static_cast<double>(buckets_.size() - 1);
    const double b = (v - vlo_) / width_;
    return b >= 0.0 ? static_cast<int>(std::min(b, last)) : 0;
  }

  void buildBuckets();

  /// Winding test of (pu, pv): against all segments (generalized winding number), or against the
  /// bucket of pv (crossing number).
  bool windingAt(double pu, double pv) const {
    const std::vector<int>* subset = buckets_.empty() ? nullptr : &buckets_[bucketOf(pv)];
    const int n = subset != nullptr ? static_cast<int>(subset->size()) : static_cast<int>(segments_.size());
    if (generalized_) {
      double angle = 0.0;
      for (int k = 0; k < n; ++k) {
        const Segment& s = segments_[subset != nullptr ? (*subset)[k] : k];
        const double ax = s.au - pu;
        const double ay = s.av - pv;
        const double bx = s.bu - pu;
        const double by = s.bv - pv;
        angle += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      }
      return std::abs(angle) >= kPi;  // |winding| >= 1/2
    }
    int winding = 0;
    for (int k = 0; k < n; ++k) {
      const Segment& s = segments_[subset != nullptr ? (*subset)[k] : k];
      const double side = (s.bu - s.au) * (pv - s.av) - (pu - s.au) * (s.bv - s.av);
      if (s.av <= pv && pv < s.bv) {
        if (side > 0.0) ++winding;  // upward crossing to the right of p
      } else if (s.bv <= pv && pv < s.av) {
        if (side < 0.0) --winding;  // downward crossing to the right of p
      }
    }
    return winding != 0;
  }

  void buildRegions(const std::vector<int>& segmentEdges);

  bool generalized_ = false;
  Vector3d u_;
  Vector3d v_;
  std::vector<Segment> segments_;
  double vlo_ = 0.0;
  double width_ = 1.0;
  std::vector<std::vector<int>> buckets_;
  std::unordered_map<int, int> regionOfTriangle_;
  std::vector<std::vector<int>> loops_;  ///< segment indices of each loop
  std::vector<int> loopRegion_;
};

}  // namespace deepcheck::decomposition::detail
