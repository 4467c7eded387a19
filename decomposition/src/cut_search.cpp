// The cut search: candidate cuts of a part, their scores and the choice (decomposer.h).

#include "decomposer.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>

namespace deepcheck::decomposition::detail {

Decomposer::SideResult Decomposer::evaluateSide(const Part& part, const std::vector<Keep>& keeps, double abortAbove) {
  SideResult result;
  std::vector<Vector3d> points;
  points.reserve(part.points.size());
  std::unordered_set<PositionKey, PositionKeyHash> crossings;
  const double slab = tol::kMinSlabRelative * diagonal_;
  const double tolerance = tol::kOnPlaneRelative * diagonal_;
  auto insideKeeps = [&](const Vector3d& x, std::size_t skip) {
    for (std::size_t k = 0; k < keeps.size(); ++k) {
      if (k != skip && keeps[k].plane.signedDistance(x) > tolerance) return false;
    }
    return true;
  };
  for (const PartPolygon& polygon : part.polygons) {
    const std::size_t n = polygon.corners.size();
    for (std::size_t e = 0; e < n; ++e) {
      const Vector3d& a = polygon.corners[e];
      const Vector3d& b = polygon.corners[(e + 1) % n];
      bool deep = true;
      for (const Keep& keep : keeps) deep = deep && keep.plane.signedDistance(a) < -slab;
      if (deep) result.valid = true;
      for (std::size_t k = 0; k < keeps.size(); ++k) {
        const double sa = keeps[k].plane.signedDistance(a);
        const double sb = keeps[k].plane.signedDistance(b);
        // Each mesh edge is crossed in the two polygons that share it: compute it once, from the
        // lexicographically smaller end, and keep the first copy.
        if (!((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0))) continue;
        const bool forward = std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        const Vector3d& from = forward ? a : b;
        const Vector3d& to = forward ? b : a;
        const double sf = forward ? sa : sb;
        const double st = forward ? sb : sa;
        const Vector3d x = from + (sf / (sf - st)) * (to - from);
        if (!insideKeeps(x, k)) continue;
        if (crossings.insert(positionKey(x)).second) points.push_back(x);
      }
    }
  }
  if (!result.valid) return result;
  for (const Vector3d& p : part.points) {
    if (insideKeeps(p, keeps.size())) points.push_back(p);  // polygon corners and cell corners
  }
  // New cell corners on each cut plane: where it meets the edges of the part's cell (and the
  // other cut plane), inside the solid and inside the part's hull (corners of other parts sharing
  // the cell stay out).
  std::vector<Halfspace> others;
  for (const CellSide& side : part.cell) others.push_back(halfspaceOf(side));
  for (const Keep& keep : keeps) others.push_back(keep.plane);
  for (const Keep& keep : keeps) {
    for (std::size_t a = 0; a < others.size(); ++a) {
      for (std::size_t b = a + 1; b < others.size(); ++b) {
        Vector3d p;
        bool feasible = planesMeet(keep.plane, others[a], others[b], &p);
        for (std::size_t i = 0; feasible && i < others.size(); ++i) {
          feasible = others[i].signedDistance(p) <= tolerance;
        }
        for (std::size_t f = 0; feasible && f < part.hull.triangles.size(); ++f) {
          feasible = part.hull.normals[f].dot(p) - part.hull.offsets[f] <= tolerance;
        }
        if (feasible && keep.section->contains(p)) points.push_back(p);
      }
    }
  }
  const Hull hull = detail::convexHull(points);
  Target target;
  target.mesh = &meshBvh_;
  addCaps(part, &target.caps);
  for (const Keep& keep : keeps) target.caps.push_back({keep.plane.normal, keep.plane.offset, keep.section});
  const Vector3d* hint = part.hasWorst ? &part.worstSample : nullptr;
  const Concavity c =
      measureConcavity(hull, target, tol::kCandidateSamples, Extra::None, nextSeed(), abortAbove, diagonal_, hint);
  result.aborted = c.aborted;
  result.concavity = c.value;
  result.volume = hull.volume;
  result.vertices = static_cast<int>(hull.vertices.size());
  return result;
}

namespace {

/// The cut directions of a part: the axes, then its principal axes unless they repeat an axis.
std::vector<Vector3d> cutDirections(const std::vector<Vector3d>& points) {
  std::vector<Vector3d> directions = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  Vector3d center = Vector3d::Zero();
  for (const Vector3d& p : points) center += p;
  center /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vector3d& p : points) cov += (p - center) * (p - center).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  for (int i = 2; i >= 0; --i) {
    const Vector3d d = solver.eigenvectors().col(i).normalized();
    bool repeated = false;
    for (const Vector3d& e : directions) repeated = repeated || std::abs(d.dot(e)) > tol::kSameDirectionCos;
    if (!repeated && d.allFinite()) directions.push_back(d);
  }
  return directions;
}

}  // namespace

/// One scoreCuts call: the part's cut directions and their extents, the cuts tried so far and
/// those scored. The steps add candidates in a fixed order (the scores and the random seeds of
/// the concavity estimates depend on it).
struct Decomposer::CutSearch {
  CutSearch(Decomposer& decomposer, const Part& cutPart, bool quickOnly, double scoreBound, double* best)
      : d(decomposer),
        part(cutPart),
        quick(quickOnly),
        bound(scoreBound),
        bestScore(*best),
        directions(cutDirections(cutPart.points)),
        tie(tol::kTieFraction * decomposer.target_),
        slab(tol::kMinSlabRelative * decomposer.diagonal_),
        wallAbove(directions.size(), kInf),
        wallBelow(directions.size(), -kInf) {
    for (const Vector3d& n : directions) ranges.push_back(extentAlong(cutPart.points, n));
    bestScore = kInf;
  }

  /// Scores the cut along directions[dir] at `offset` unless it is (almost) tried already.
  void tryCut(int dir, double offset, bool throughWorst);
  /// Through the worst hull sample and through the mesh point nearest to it.
  void throughWorstCuts();
  /// Through the part's points near the worst sample.
  void nearWorstCuts();
  /// Through the walls that rays from the worst sample meet, and along the walls' planes.
  void wallCuts();
  /// Slabs between the walls on both sides of the worst sample.
  void slabCuts();
  /// Evenly spaced offsets along each direction.
  void evenCuts();
  /// Refines the offset of the best cut.
  void refine();

  Decomposer& d;
  const Part& part;
  const bool quick;
  const double bound;
  double& bestScore;
  std::vector<Vector3d> directions;
  std::vector<Extent> ranges;
  const double tie;
  const double slab;
  std::vector<Candidate> scored;
  std::vector<std::pair<int, double>> tried;
  /// Where the rays from the worst sample meet a wall, per direction (wallCuts).
  std::vector<double> wallAbove;
  std::vector<double> wallBelow;
};

void Decomposer::CutSearch::tryCut(int dir, double offset, bool throughWorst) {
  const Extent& r = ranges[dir];
  if (!(offset > r.lo + slab && offset < r.hi - slab)) return;
  // A plane (almost) tried already: the same cut.
  for (const auto& [t, o] : tried) {
    if (t == dir && std::abs(o - offset) <= tol::kSameOffsetFraction * d.target_) return;
  }
  tried.emplace_back(dir, offset);
  const Vector3d& n = directions[dir];
  const CrossSection section(d.mesh_, n, offset, false);
  double abortAbove = std::min(bestScore + tie, bound);
  if (part.reductionLimited) abortAbove = std::max(abortAbove, d.target_);
  const SideResult a = d.evaluateSide(part, {{{n, offset}, &section}}, abortAbove);
  if (!a.valid || a.aborted) return;
  const SideResult b = d.evaluateSide(part, {{{-n, -offset}, &section}}, abortAbove);
  if (!b.valid || b.aborted) return;
  if (part.noSlivers && std::min(a.volume, b.volume) < (1.0 - tol::kSliverVolume) * part.hull.volume) return;
  const double score = std::max(a.concavity, b.concavity);
  bestScore = std::min(bestScore, score);
  double faceArea = 0.0;
  const double onPlane = tol::kOnPlaneRelative * d.diagonal_;
  for (const PartPolygon& polygon : part.polygons) {
    bool inPlane = true;
    for (const Vector3d& p : polygon.corners) inPlane = inPlane && std::abs(n.dot(p) - offset) <= onPlane;
    if (!inPlane) continue;
    faceArea += 0.5 * doubleVectorArea(polygon.corners).norm();
  }
  scored.push_back(
      {{n, offset}, score, a.volume + b.volume, std::max(a.vertices, b.vertices), throughWorst, faceArea, dir});
}

void Decomposer::CutSearch::throughWorstCuts() {
  // The worst hull sample is the middle of the deepest concavity: cutting there splits it; the
  // mesh point nearest to it is the bottom of the concavity.
  for (int k = 0; k < static_cast<int>(directions.size()); ++k) {
    tryCut(k, directions[k].dot(part.worstSample), true);
    tryCut(k, directions[k].dot(part.worstNearest), false);
  }
}

void Decomposer::CutSearch::nearWorstCuts() {
  // The walls, floors and edges that bound the concavity (the walls of a slot, the rim of a
  // hole), which the planes through the worst sample may miss.
  const double radius = 1.5 * part.concavity + d.target_;
  std::vector<const Vector3d*> near;
  for (const Vector3d& p : part.points) {
    if ((p - part.worstSample).norm() <= radius) near.push_back(&p);
  }
  for (int k = 0; k < static_cast<int>(directions.size()); ++k) {
    const double center = directions[k].dot(part.worstSample);
    std::vector<double> values;
    for (const Vector3d* p : near) values.push_back(directions[k].dot(*p));
    std::sort(values.begin(), values.end(),
              [&](double a, double b) { return std::abs(a - center) < std::abs(b - center); });
    std::vector<double> chosen;
    for (double v : values) {
      bool close = false;
      for (double c : chosen) close = close || std::abs(c - v) <= tol::kFeatureSpacingFraction * d.target_;
      if (!close) chosen.push_back(v);
      if (static_cast<int>(chosen.size()) >= (quick ? tol::kQuickFeatureOffsets : tol::kFeatureOffsets)) break;
    }
    for (double v : chosen) tryCut(k, v, false);
  }
}

void Decomposer::CutSearch::wallCuts() {
  // The first surface hit by rays from the worst sample along each direction, both ways (the
  // floor, ceiling and sides of a pocket or slot, which may be farther than the points near the
  // sample). The plane of the wall hit is a candidate too (a drafted wall is not axis-aligned).
  const int fixedDirections = static_cast<int>(directions.size());
  for (int k = 0; k < fixedDirections; ++k) {
    for (double sign : {1.0, -1.0}) {
      const Vector3d dir = sign * directions[k];
      double nearest = kInf;
      const PartPolygon* wall = nullptr;
      for (const PartPolygon& polygon : part.polygons) {
        for (std::size_t c = 1; c + 1 < polygon.corners.size(); ++c) {
          const double t = detail::rayTriangle(part.worstSample, dir, polygon.corners[0], polygon.corners[c],
                                               polygon.corners[c + 1]);
          if (t > 0.0 && t < nearest) {
            nearest = t;
            wall = &polygon;
          }
        }
      }
      if (!std::isfinite(nearest)) continue;
      const Vector3d hit = part.worstSample + nearest * dir;
      tryCut(k, directions[k].dot(hit), false);
      (sign > 0.0 ? wallAbove : wallBelow)[k] = directions[k].dot(hit);
      Vector3d normal = doubleVectorArea(wall->corners);
      if (!(normal.norm() > 0.0)) continue;
      normal.normalize();
      bool known = false;
      for (const Vector3d& e : directions) known = known || std::abs(normal.dot(e)) > 1.0 - tol::kOnPlaneNormal;
      if (known) continue;
      directions.push_back(normal);
      ranges.push_back(extentAlong(part.points, normal));
      tryCut(static_cast<int>(directions.size()) - 1, normal.dot(hit), false);
    }
  }
}

void Decomposer::CutSearch::slabCuts() {
  // A slot, groove or gap between two walls is cut out in one step (three parts), which no
  // single cut shows as progress.
  for (int k = 0; k < static_cast<int>(wallAbove.size()); ++k) {
    const double lo = wallBelow[k];
    const double hi = wallAbove[k];
    const Extent& r = ranges[k];
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo > r.lo + slab && hi < r.hi - slab && hi - lo > 2.0 * slab)) {
      continue;
    }
    const Vector3d& n = directions[k];
    const CrossSection sectionLo(d.mesh_, n, lo, false);
    const CrossSection sectionHi(d.mesh_, n, hi, false);
    const double abortAbove = std::min(bestScore + tie, bound);
    const SideResult a = d.evaluateSide(part, {{{n, lo}, &sectionLo}}, abortAbove);
    if (!a.valid || a.aborted) continue;
    const SideResult b = d.evaluateSide(part, {{{-n, -lo}, &sectionLo}, {{n, hi}, &sectionHi}}, abortAbove);
    if (!b.valid || b.aborted) continue;
    const SideResult c = d.evaluateSide(part, {{{-n, -hi}, &sectionHi}}, abortAbove);
    if (!c.valid || c.aborted) continue;
    const double score = std::max({a.concavity, b.concavity, c.concavity});
    bestScore = std::min(bestScore, score);
    Candidate slabCut{
        {n, lo}, score, a.volume + b.volume + c.volume, std::max({a.vertices, b.vertices, c.vertices}), false, 0.0, k};
    slabCut.slabOffset = hi;
    scored.push_back(slabCut);
  }
}

void Decomposer::CutSearch::evenCuts() {
  const int offsets = tol::kOffsetsPerDirection;
  for (int k = 0; k < static_cast<int>(directions.size()); ++k) {
    const Extent& r = ranges[k];
    for (int i = 0; i < offsets; ++i) tryCut(k, r.lo + (r.hi - r.lo) * (i + 0.5) / offsets, false);
  }
}

void Decomposer::CutSearch::refine() {
  for (int round = 1; round <= tol::kRefinementRounds; ++round) {
    const Candidate* pick = d.pickBest(part, scored, bestScore);
    if (pick->isSlab()) break;
    const int dir = pick->direction;
    const double offset = pick->cut.offset;
    const Extent& r = ranges[dir];
    const double step = (r.hi - r.lo) / tol::kOffsetsPerDirection / std::pow(2.0, round);
    tryCut(dir, offset - step, false);
    tryCut(dir, offset + step, false);
  }
}

std::vector<Decomposer::Candidate> Decomposer::scoreCuts(const Part& part, bool quick, double bound,
                                                         double* bestScore) {
  CutSearch search(*this, part, quick, bound, bestScore);
  if (part.hasWorst) {
    search.throughWorstCuts();
    search.nearWorstCuts();
    search.wallCuts();
  }
  search.slabCuts();
  // The lookahead's second cut: the planes near the concavity only.
  if (quick) return std::move(search.scored);
  search.evenCuts();
  if (search.scored.empty()) return std::move(search.scored);
  search.refine();
  return std::move(search.scored);
}

bool Decomposer::betterTie(const Candidate& a, const Candidate& b) const {
  const double areaTie = tol::kFaceAreaTie * diagonal_ * diagonal_;
  if (std::abs(a.faceArea - b.faceArea) > areaTie) return a.faceArea > b.faceArea;
  return a.volume < b.volume;
}

const Decomposer::Candidate* Decomposer::pickBest(const Part& part, const std::vector<Candidate>& scored,
                                                  double bestScore) const {
  // Among the cuts within `tie` of the best score: the one along the most mesh face area first
  // (cutting along a wall of a pocket or slot is progress that the concavities only show once
  // all its walls are cut), then the smaller sum of hull volumes. A part cut only because its reduced hull misses the
  // target (reductionLimited) needs fewer hull vertices per side rather than less concavity: among the cuts whose sides
  // meet the target, the smaller larger vertex count wins.
  const double tie = tol::kTieFraction * target_;
  const Candidate* pick = nullptr;
  if (part.reductionLimited) {
    for (const Candidate& s : scored) {
      if (s.score > target_) continue;
      if (pick == nullptr || s.vertices < pick->vertices || (s.vertices == pick->vertices && s.volume < pick->volume)) {
        pick = &s;
      }
    }
    if (pick != nullptr) return pick;
  }
  for (const Candidate& s : scored) {
    if (s.score > bestScore + tie) continue;
    if (pick == nullptr || betterTie(s, *pick)) pick = &s;
  }
  return pick;
}

std::vector<const Decomposer::Candidate*> Decomposer::lookaheadOrder(const Part& part,
                                                                     const std::vector<Candidate>& scored,
                                                                     const Candidate* pick) const {
  // First cuts tried: through the worst sample (a hole needs two of those), the nearest cut on
  // each side of it along each direction (a slot needs one along each wall), and the best scores.
  std::vector<const Candidate*> order = {pick};
  auto add = [&](const Candidate* c) {
    if (c != nullptr && std::find(order.begin(), order.end(), c) == order.end()) order.push_back(c);
  };
  // Equal scores are common on a plateau: the axes and principal directions go first.
  auto byScore = [](const Candidate* a, const Candidate* b) {
    if (a->score != b->score) return a->score < b->score;
    if (a->direction != b->direction) return a->direction < b->direction;
    return a->volume < b->volume;
  };
  std::vector<const Candidate*> through;
  std::vector<const Candidate*> walls;
  for (const Candidate& c : scored) {
    if (c.throughWorst) {
      through.push_back(&c);
      continue;
    }
    // Is c the nearest cut on its side of the worst sample, along its direction?
    const double x = c.cut.signedDistance(part.worstSample);
    bool nearest = true;
    for (const Candidate& o : scored) {
      if (o.throughWorst || &o == &c || (o.cut.normal - c.cut.normal).squaredNorm() > 0.0) continue;
      const double y = o.cut.signedDistance(part.worstSample);
      if ((x > 0.0) == (y > 0.0) && std::abs(y) < std::abs(x)) nearest = false;
    }
    if (nearest) walls.push_back(&c);
  }
  std::sort(through.begin(), through.end(), byScore);
  std::sort(walls.begin(), walls.end(), byScore);
  for (std::size_t k = 0; k < std::max(through.size(), walls.size()); ++k) {
    if (k < through.size()) add(through[k]);
    if (k < walls.size()) add(walls[k]);
  }
  std::vector<const Candidate*> ranked;
  for (const Candidate& c : scored) ranked.push_back(&c);
  std::sort(ranked.begin(), ranked.end(), byScore);
  for (int k = 0; k < tol::kLookaheadBest && k < static_cast<int>(ranked.size()); ++k) {
    order.insert(order.begin() + std::min<std::size_t>(order.size(), 1 + k), ranked[k]);
  }
  // Duplicates from the insertion above are dropped.
  std::vector<const Candidate*> unique;
  for (const Candidate* c : order) {
    if (std::find(unique.begin(), unique.end(), c) == unique.end()) unique.push_back(c);
  }
  if (static_cast<int>(unique.size()) > tol::kLookaheadCuts) unique.resize(tol::kLookaheadCuts);
  return unique;
}

const Decomposer::Candidate* Decomposer::lookahead(const Part& part, const std::vector<const Candidate*>& order,
                                                   const Candidate* pick, std::vector<Part>* children,
                                                   double* bestAhead) {
  const double tie = tol::kTieFraction * target_;
  *bestAhead = kInf;
  const Candidate* bestCandidate = nullptr;
  for (const Candidate* candidate : order) {
    std::vector<Part> kids = candidate == pick ? std::move(*children) : applyCut(part, *candidate, false);
    double ahead = 0.0;
    for (const Part& kid : kids) {
      double next = kid.concavity;
      if (next > target_) {
        double quickBest = kInf;
        scoreCuts(kid, true, std::min(*bestAhead + tie, next), &quickBest);
        next = std::min(next, quickBest);
      }
      ahead = std::max(ahead, next);
      if (ahead > *bestAhead + tie) break;
    }
    if (ahead < *bestAhead - tie ||
        (ahead <= *bestAhead + tie && (bestCandidate == nullptr || betterTie(*candidate, *bestCandidate)))) {
      *bestAhead = std::min(*bestAhead, ahead);
      bestCandidate = candidate;
      *children = std::move(kids);
    }
  }
  return bestCandidate;
}

bool Decomposer::chooseSplit(const Part& part, std::vector<Part>* children) {
  double bestScore = kInf;
  std::vector<Candidate> scored = scoreCuts(part, false, kInf, &bestScore);
  if (scored.empty()) return false;
  const Candidate* pick = pickBest(part, scored, bestScore);
  // The children are reduced to the vertex budget only once chosen (finishChildren).
  auto finishChildren = [&]() {
    for (Part& kid : *children) finishPart(&kid);
    return !children->empty();
  };
  *children = applyCut(part, *pick, false);
  // The sides' concavities as the children measure them (more samples than the candidates had).
  double greedy = 0.0;
  for (const Part& kid : *children) greedy = std::max(greedy, kid.concavity);
  const bool plateau = !part.reductionLimited && greedy > target_ && greedy > tol::kPlateauFraction * part.concavity;
  if (!plateau) return finishChildren();
  // Plateau: no single cut lowers the worst concavity (a slot needs a cut along each wall, a hole
  // two cuts through its axis). Look one cut ahead: split by each of the most promising cuts, and
  // score it by the worst concavity left after the best quick cut of each side that misses the
  // target.
  double bestAhead = kInf;
  const Candidate* bestCandidate = lookahead(part, lookaheadOrder(part, scored, pick), pick, children, &bestAhead);
  // Still no progress two cuts deep (a frame around a pocket needs a cut along each of its
  // walls before any concavity drops): cut along the largest mesh face near the concavity.
  if (bestAhead > tol::kStructuralFraction * part.concavity) {
    const double tie = tol::kTieFraction * target_;
    const Candidate* structural = nullptr;
    for (const Candidate& c : scored) {
      if (c.faceArea <= tol::kFaceAreaTie * diagonal_ * diagonal_ || c.score > part.concavity + tie) continue;
      if (structural == nullptr || betterTie(c, *structural)) structural = &c;
    }
    if (structural != nullptr && structural != bestCandidate) *children = applyCut(part, *structural, false);
  }
  return finishChildren();
}

std::vector<Part> Decomposer::applyCut(const Part& part, const Candidate& candidate, bool reduce) {
  std::vector<Part> first = split(part, candidate.cut, reduce && !candidate.isSlab());
  if (!candidate.isSlab()) return first;
  // The second plane of the slab cuts the parts above the first one.
  const Halfspace upper{candidate.cut.normal, candidate.slabOffset};
  std::vector<Part> out;
  for (Part& kid : first) {
    const Extent e = extentAlong(kid.points, upper.normal);
    const double slab = tol::kMinSlabRelative * diagonal_;
    if (e.lo < upper.offset - slab && e.hi > upper.offset + slab) {
      for (Part& piece : split(kid, upper, reduce)) out.push_back(std::move(piece));
    } else {
      if (reduce) finishPart(&kid);
      out.push_back(std::move(kid));
    }
  }
  return out;
}

std::vector<Part> Decomposer::split(const Part& part, const Halfspace& cut, bool reduce) {
  const int plane = static_cast<int>(planes_.size());
  planes_.push_back(
      std::make_unique<CutPlane>(CutPlane{cut.normal, cut.offset, CrossSection(mesh_, cut.normal, cut.offset, true)}));
  std::vector<Part> children;
  for (bool flipped : {false, true}) {
    const Halfspace keep = flipped ? cut.flipped() : cut;
    std::vector<CellSide> cell = part.cell;
    cell.push_back({plane, flipped});
    for (Component& component : components(clip(part.polygons, keep), cell)) {
      children.push_back(makePart(cell, std::move(component.polygons), std::move(component.cellCorners), reduce,
                                  part.hasWorst ? &part.worstSample : nullptr));
    }
  }
  return children;
}

}  // namespace deepcheck::decomposition::detail
