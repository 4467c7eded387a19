// The Gauss-map walk (DEEP's walks) and the query: walks from the warm start's basins or the cold
// start directions, the best end is the answer, the best distinct ends are the next warm query's
// basins. Also the facet at one direction without a walk (facetInDirection: a walk's first
// facet), with which the certified method names answers on parallel faces. Vocabulary in deep_walker.h; the facets a
// walk moves over come from deep_facets.cpp.

#include "deep_walker.h"

#include "deepcheck/geometry/internal/walk_scratch.h"

namespace deepcheck::geometry::detail {

WalkScratch::WalkScratch() : data_(std::make_unique<WalkScratchData>()) {}
WalkScratch::~WalkScratch() = default;
WalkScratch::WalkScratch(WalkScratch&&) noexcept = default;
WalkScratch& WalkScratch::operator=(WalkScratch&&) noexcept = default;

WalkEnd walk(Walker& w, Candidate start, int maxHubs, WalkStats& stats) {
  WalkEnd end;
  end.facet = start;
  int next[4];
  // Hub pairs at the corners of the current facet, copied out of the scratch space.
  constexpr int kMaxCorners = 64;
  int cornerA[kMaxCorners], cornerB[kMaxCorners];
  for (int hubs = 0; hubs < maxHubs;) {
    if (w.footInFacet(end.facet, end.pA, end.pB, next)) {
      // The foot is in the facet (a KKT point). A facet sharing one of its corners may still lie
      // closer to the origin; only when none does is this a local minimum of the walk.
      end.witnessed = true;
      const int nc = std::min(w.numFacetCorners(), kMaxCorners);
      for (int k = 0; k < nc; ++k) w.facetCorner(k, cornerA[k], cornerB[k]);
      Candidate bestNear;
      for (int k = 0; k < nc; ++k) {
        if (w.isVisited(cornerA[k], cornerB[k])) continue;
        Candidate c;
        ++hubs;
        if (w.hub(cornerA[k], cornerB[k], c, stats) && c.d < bestNear.d) bestNear = c;
      }
      if (bestNear.valid() && bestNear.d < end.facet.d - w.tolImprove()) {
        w.markVisited(bestNear.hubA, bestNear.hubB);
        end.facet = bestNear;
        end.witnessed = false;
        ++stats.steps;
        continue;
      }
      end.converged = true;
      return end;
    }
    end.witnessed = false;
    bool moved = false;
    for (int option = 0; option < 2 && !moved; ++option) {
      const int ia = next[2 * option], ib = next[2 * option + 1];
      if (ia < 0) continue;
      if (w.isVisited(ia, ib)) {
        // An earlier walk moved through this hub pair: from here on it follows the same path.
        end.joined = true;
        return end;
      }
      Candidate c;
      ++hubs;
      if (w.hub(ia, ib, c, stats) && c.d < end.facet.d - w.tolImprove()) {
        w.markVisited(ia, ib);
        end.facet = c;
        ++stats.steps;
        moved = true;
      }
    }
    if (!moved) {
      // The foot lies outside the facet, yet no neighbour improves by more than round-off:
      // a numerically flat spot. The facet is still a valid separating direction.
      end.converged = true;
      return end;
    }
  }
  return end;
}

namespace {

/// The walks of one query: where they ended and the best end so far.
class Walks {
 public:
  Walks(Walker& w, const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const WalkOptions& options,
        WalkStats& stats)
      : w_(w), A_(A), B_(B), frame_(frame), options_(options), stats_(stats) {
    best_.facet.d = std::numeric_limits<double>::infinity();
    // The origin lies off M's centre by -t: the nearest boundary is most likely that way.
    centroidDir_ = frame.t.norm() > 0 ? Vec3(-frame.t.normalized()) : Vec3(Vec3::UnitZ());
  }

  void warmStarts(const WalkCache& cache);
  void coldStarts();
  /// Fills the answer from the best end; counts the walks that ended in a worse local minimum.
  void answer(WalkResult& result);
  /// Basins for the next warm query: the answer first, then the best other distinct ends.
  void rememberBasins(WalkCache& cache, bool warm);

 private:
  void runFrom(int ia, int ib);

  Walker& w_;
  const ConvexPolytope& A_;
  const ConvexPolytope& B_;
  const PairFrame& frame_;
  const WalkOptions& options_;
  WalkStats& stats_;
  Vec3 centroidDir_;
  WalkEnd best_;
  // Where walks ended: to count those that stopped in a worse local minimum, and to remember
  // the best distinct ones as basins for the next warm query.
  static constexpr int kMaxEnds = 32;
  Candidate ends_[kMaxEnds];
  int ended_ = 0;
};

void Walks::runFrom(int ia, int ib) {
  if (w_.isVisited(ia, ib)) return;
  w_.markVisited(ia, ib);
  Candidate c;
  if (!w_.hub(ia, ib, c, stats_)) return;
  ++stats_.starts;
  WalkEnd e = walk(w_, c, options_.maxHubsPerWalk, stats_);
  if (!e.joined && ended_ < kMaxEnds) ends_[ended_++] = e.facet;
  if (e.facet.d < best_.facet.d || (e.facet.d == best_.facet.d && e.witnessed && !best_.witnessed)) {
    best_ = e;
  }
}

void Walks::warmStarts(const WalkCache& cache) {
  stats_.warm = true;
  int ia = 0, ib = 0;
  for (int k = 0; k < cache.count; ++k) {
    const int hintA = std::clamp(cache.hubA[k], 0, A_.numVertices() - 1);
    const int hintB = std::clamp(cache.hubB[k], 0, B_.numVertices() - 1);
    w_.hubFor(cache.u[k], ia, ib, hintA, hintB);
    runFrom(ia, ib);
  }
  if (options_.warmCentroidStart) {
    w_.hubFor(centroidDir_, ia, ib, ia, ib);
    runFrom(ia, ib);
  }
}

void Walks::coldStarts() {
  int ia = 0, ib = 0;
  w_.hubFor(centroidDir_, ia, ib, 0, 0);
  runFrom(ia, ib);
  if (!options_.restarts) return;
  // The other starts: the opposite direction and both signs of each shape's principal axes.
  constexpr int kStarts = 13;
  Vec3 dirs[kStarts];
  dirs[0] = -centroidDir_;
  const Eigen::Matrix3d axesA = A_.principalAxes();
  const Eigen::Matrix3d axesB = frame_.R * B_.principalAxes();
  for (int k = 0; k < 3; ++k) {
    dirs[1 + 4 * k] = axesA.col(k);
    dirs[2 + 4 * k] = -axesA.col(k);
    dirs[3 + 4 * k] = axesB.col(k);
    dirs[4 + 4 * k] = -axesB.col(k);
  }
  int hubsA[kStarts], hubsB[kStarts], order[kStarts];
  double offset[kStarts];
  for (int k = 0; k < kStarts; ++k) {
    w_.hubFor(dirs[k], hubsA[k], hubsB[k], ia, ib);
    ia = hubsA[k];
    ib = hubsB[k];
    offset[k] = dirs[k].dot(w_.vb(ib) - w_.va(ia));
    order[k] = k;
  }
  if (options_.pruneRestarts) {
    std::sort(order, order + kStarts, [&](int x, int y) { return offset[x] < offset[y]; });
  }
  for (int j = 0; j < kStarts; ++j) {
    const int k = order[j];
    if (options_.pruneRestarts && offset[k] >= best_.facet.d - w_.tolImprove()) break;
    runFrom(hubsA[k], hubsB[k]);
  }
}

/// The answer's depth, normal, type and features from facet f.
void setFacet(const Candidate& f, WalkResult& result) {
  result.depth = f.d;
  result.normal = -f.u;
  result.type = f.type;
  result.featureA = f.fa;
  result.featureA2 = f.fa2;
  result.featureB = f.fb;
  result.featureB2 = f.fb2;
}

void Walks::answer(WalkResult& result) {
  for (int k = 0; k < ended_; ++k) {
    if (ends_[k].d > best_.facet.d + w_.tolImprove()) ++stats_.localMinima;
  }
  const Candidate& f = best_.facet;
  result.status = best_.converged ? WalkStatus::Converged : WalkStatus::NotConverged;
  setFacet(f, result);
  int next[4];
  if (best_.witnessed) {
    result.pointA = best_.pA;
    result.pointB = best_.pB;
  } else if (!w_.footInFacet(f, result.pointA, result.pointB, next)) {
    result.pointB = w_.vb(f.hubB);
    result.pointA = result.pointB + f.d * result.normal;
  }
}

void Walks::rememberBasins(WalkCache& cache, bool warm) {
  cache.valid = true;
  cache.warmQueries = warm ? cache.warmQueries + 1 : 0;
  cache.count = 0;
  auto remember = [&](const Candidate& c) {
    for (int k = 0; k < cache.count; ++k) {
      if (cache.hubA[k] == c.hubA && cache.hubB[k] == c.hubB) return;
    }
    if (cache.count == WalkCache::kBasins) return;
    cache.hubA[cache.count] = c.hubA;
    cache.hubB[cache.count] = c.hubB;
    cache.u[cache.count] = c.u;
    ++cache.count;
  };
  remember(best_.facet);
  std::sort(ends_, ends_ + ended_, [](const Candidate& x, const Candidate& y) { return x.d < y.d; });
  for (int k = 0; k < ended_; ++k) remember(ends_[k]);
}

}  // namespace

WalkResult walkPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, WalkCache* cache,
                           const WalkOptions& options, bool warmStart, WalkScratch* scratch) {
  WalkScratchData local;  // allocates only what this query uses
  WalkResult result;
  Walker w(A, B, frame, scratch ? scratch->data() : local);
  if (lowDimPenetration(w, A, B, frame, result)) return result;

  // General case: walks on the Minkowski difference.
  Walks walks(w, A, B, frame, options, result.stats);
  const bool warm = warmStart && cache && cache->valid && cache->count > 0 &&
                    (options.refreshEvery <= 0 || cache->warmQueries < options.refreshEvery);
  if (warm) walks.warmStarts(*cache);
  else walks.coldStarts();
  walks.answer(result);
  if (cache) walks.rememberBasins(*cache, warm);
  return result;
}

WalkResult facetInDirection(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                            const Eigen::Vector3d& u, int hintA, int hintB, WalkScratch* scratch) {
  WalkScratchData local;
  WalkResult result;
  Walker w(A, B, frame, scratch ? scratch->data() : local);
  int ia = 0, ib = 0;
  w.hubFor(u, ia, ib, hintA, hintB);
  Candidate c;
  int next[4];
  if (!w.hub(ia, ib, c, result.stats) || !w.footInFacet(c, result.pointA, result.pointB, next)) return result;
  result.status = WalkStatus::Converged;
  setFacet(c, result);
  return result;
}

}  // namespace deepcheck::geometry::detail
