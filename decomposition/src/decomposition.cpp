// Approximate convex decomposition: the driver (decomposer.h describes the
// algorithm, decomposition.h the contract).

#include "decomposer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepcheck::decomposition {

namespace detail {

void Decomposer::addPart(std::vector<Piece>* pieces, Part part) {
  pieces->push_back({{static_cast<int>(parts_.size())}, part.hull, part.finalHull, part.concavity});
  parts_.push_back(std::move(part));
}

std::vector<Piece> Decomposer::initialPieces(DecompositionReport* report) {
  // The whole mesh as one part: if its hull meets the target, it is the answer.
  std::vector<PartPolygon> all;
  all.reserve(mesh_.triangles.size());
  for (int t = 0; t < static_cast<int>(mesh_.triangles.size()); ++t) {
    const auto& tri = mesh_.triangles[t];
    all.push_back({{mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]}, t});
  }
  std::vector<Piece> pieces;
  Part whole = makePart({}, all, {});
  report->hullConcavity = whole.hullConcavity;
  // A mesh whose own hull meets the target stays one piece, even when reducing that hull to the
  // vertex budget adds more than the target allows: the report (and its warning) then says so.
  report->alreadyConvex = whole.hullConcavity <= target_;
  if (report->alreadyConvex || mesh_.numGroups == 1) {
    addPart(&pieces, std::move(whole));
  } else {
    std::vector<std::vector<PartPolygon>> byGroup(mesh_.numGroups);
    for (const PartPolygon& polygon : all) byGroup[mesh_.group[polygon.source]].push_back(polygon);
    for (auto& polygons : byGroup) addPart(&pieces, makePart({}, std::move(polygons), {}));
  }
  return pieces;
}

bool Decomposer::reopen(std::vector<Piece>* pieces, const std::vector<Concavity>& final, bool forbidAll) {
  std::vector<Piece> next;
  bool changed = false;
  for (std::size_t i = 0; i < pieces->size(); ++i) {
    Piece& piece = (*pieces)[i];
    if (final[i].value <= reportTarget_) {
      next.push_back(std::move(piece));
      continue;
    }
    changed = true;
    if (piece.parts.size() == 1) {
      Part& part = parts_[piece.parts.front()];
      part.concavity = std::max(part.concavity, final[i].value);
      part.hasWorst = final[i].hasWorst;
      part.worstSample = final[i].worstSample;
      part.worstNearest = final[i].worstNearest;
      piece.concavity = part.concavity;
      next.push_back(std::move(piece));
    } else {
      const bool forbid = forbidAll || piece.concavity <= target_;
      for (int a : piece.parts) {
        if (forbid) {
          for (int b : piece.parts) forbidden_.insert({a, b});
        }
        next.push_back({{a}, parts_[a].hull, parts_[a].finalHull, parts_[a].concavity});
      }
    }
  }
  *pieces = std::move(next);
  return changed;
}

bool Decomposer::cutWorst(std::vector<Piece>* pieces) {
  int worst = -1;
  for (int i = 0; i < static_cast<int>(pieces->size()); ++i) {
    const Piece& piece = (*pieces)[i];
    if (piece.parts.size() != 1 || piece.concavity <= target_) continue;
    if (parts_[piece.parts.front()].unsplittable) continue;
    if (worst < 0 || piece.concavity > (*pieces)[worst].concavity) worst = i;
  }
  if (worst < 0) return false;
  const int index = (*pieces)[worst].parts.front();
  std::vector<Part> children;
  if (!chooseSplit(parts_[index], &children) || children.empty()) {
    parts_[index].unsplittable = true;
    return true;
  }
  // A cut that only shaves a sliver off (a child with nearly the part's hull volume and its
  // concavity) is no progress: the part is left as it is.
  bool stuck = false;
  for (const Part& child : children) {
    stuck = stuck || (child.hull.volume >= tol::kSliverVolume * parts_[index].hull.volume &&
                      child.concavity >= parts_[index].concavity - tol::kTieFraction * target_);
  }
  if (stuck) {
    // Once more without the sliver cuts, then give up on this part.
    if (parts_[index].noSlivers) parts_[index].unsplittable = true;
    parts_[index].noSlivers = true;
    return true;
  }
  pieces->erase(pieces->begin() + worst);
  for (Part& child : children) addPart(pieces, std::move(child));
  return true;
}

void Decomposer::cutAndMerge(std::vector<Piece>* pieces, bool alreadyConvex) {
  for (int round = 0; round < tol::kMaxRounds && !alreadyConvex; ++round) {
    while (static_cast<int>(pieces->size()) < budget_ && cutWorst(pieces)) reportProgress(*pieces);
    bool over = false;
    for (const Piece& piece : *pieces) over = over || piece.concavity > target_;
    if (!params_.mergePieces) break;
    const std::size_t before = pieces->size();
    *pieces = merge(std::move(*pieces), false);
    if (!over || pieces->size() == before) break;
  }
  if (!alreadyConvex) *pieces = merge(std::move(*pieces), true);
}

void Decomposer::reportProgress(const std::vector<Piece>& pieces) {
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - lastProgress_).count() < tol::kProgressSeconds) return;
  lastProgress_ = now;
  double worst = 0.0;
  for (const Piece& piece : pieces) worst = std::max(worst, piece.concavity);
  std::fprintf(stderr,
               "deepcheck: decomposing %s (%zu triangles): %zu pieces, worst concavity %s (target %s), %.0f s\n",
               name_.c_str(), mesh_.triangles.size(), pieces.size(), roundedNumber(worst).c_str(),
               roundedNumber(reportTarget_).c_str(), std::chrono::duration<double>(now - start_).count());
}

void Decomposer::capVertices(std::vector<Piece>* pieces) {
  for (Piece& piece : *pieces) {
    if (static_cast<int>(piece.finalHull.vertices.size()) <= params_.maxVerticesPerPiece) continue;
    piece.finalHull = detail::reduceHullVertices(piece.hull, params_.maxVerticesPerPiece);
    if (piece.parts.size() == 1) parts_[piece.parts.front()].finalHull = piece.finalHull;
  }
}

std::vector<Concavity> Decomposer::finalConcavities(const std::vector<Piece>& pieces) {
  std::vector<Concavity> final;
  for (const Piece& piece : pieces) {
    final.push_back(measureConcavity(piece.finalHull, pieceTarget(piece, nullptr), tol::kReportSamples, Extra::Dense,
                                     nextSeed(), kInf, diagonal_));
  }
  return final;
}

std::vector<ConvexPiece> Decomposer::run(DecompositionReport* report) {
  std::vector<Piece> pieces = initialPieces(report);
  // Rounds: cut the worst part until all meet the target or the budget is spent; then merge the
  // neighbours that can be merged, which frees budget for more cuts. Then verify: the final,
  // denser estimate may find a piece above the target that the decisions' estimate missed (a small
  // hole spanned by a hull): such a piece is cut further (or, if merged, split back into its
  // parts) while the budget lasts.
  //
  // Budget stages: all of this runs first with at most kFirstPieceBudget pieces; only when the
  // target is still missed does it go on from there (the pieces above the target reopened) with
  // twice the budget, up to maxPieces. A mesh that meets the target within the first budget gets
  // the same pieces whatever maxPieces is, and a larger maxPieces costs nothing for it.
  std::vector<Concavity> final;
  for (budget_ = std::min(params_.maxPieces, tol::kFirstPieceBudget);;
       budget_ = static_cast<int>(std::min<long long>(2LL * budget_, params_.maxPieces))) {
    for (int verify = 0; verify <= tol::kVerifyRounds; ++verify) {
      cutAndMerge(&pieces, report->alreadyConvex);
      capVertices(&pieces);
      final = finalConcavities(pieces);  // the final, denser estimate on what is returned
      if (verify == tol::kVerifyRounds || report->alreadyConvex) break;
      if (!reopen(&pieces, final, true)) break;
    }
    if (report->alreadyConvex || budget_ >= params_.maxPieces) break;
    bool met = true;
    for (const Concavity& c : final) met = met && c.value <= reportTarget_;
    if (met) break;
    reopen(&pieces, final, false);
  }
  std::vector<ConvexPiece> out;
  report->concavity = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Hull& hull = pieces[i].finalHull;
    report->concavity = std::max(report->concavity, final[i].value);
    out.push_back({hull.vertices, hull.triangles, hull.volume, final[i].value});
  }
  return out;
}

}  // namespace detail

using detail::CleanMesh;
using detail::cleanMesh;
using detail::Decomposer;
using detail::formatNumber;
using detail::kInf;
using Eigen::Vector3d;

// ------------------------------------------------------------------------------------------------

double DecompositionParams::targetConcavity(double diagonal) const {
  return std::max(maxConcavity * diagonal, minConcavityAbs);
}

void DecompositionParams::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("DecompositionParams: " + what); };
  if (!(maxConcavity > 0.0 && maxConcavity <= 1.0)) {
    fail("maxConcavity must be in (0, 1] (a fraction of the bounding-box diagonal), got " + formatNumber(maxConcavity));
  }
  if (!(minConcavityAbs >= 0.0 && std::isfinite(minConcavityAbs))) {
    fail("minConcavityAbs must be finite and >= 0, got " + formatNumber(minConcavityAbs));
  }
  if (maxPieces < 1) fail("maxPieces must be >= 1, got " + std::to_string(maxPieces));
  if (maxTriangles < 1) fail("maxTriangles must be >= 1, got " + std::to_string(maxTriangles));
  if (maxVerticesPerPiece < 4) {
    fail("maxVerticesPerPiece must be >= 4, got " + std::to_string(maxVerticesPerPiece));
  }
}

const char* toString(CacheStatus status) {
  switch (status) {
    case CacheStatus::NotUsed:
      return "not used";
    case CacheStatus::Hit:
      return "hit";
    case CacheStatus::Stored:
      return "stored";
    case CacheStatus::Replaced:
      return "replaced";
    case CacheStatus::StoreFailed:
      return "store failed";
  }
  return "?";
}

std::vector<geometry::ConvexPolytope> ConvexDecomposition::polytopes() const {
  std::vector<geometry::ConvexPolytope> out;
  out.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::string name =
        (report.source.empty() ? std::string("mesh") : report.source) + " piece " + std::to_string(i);
    out.push_back(geometry::ConvexPolytope::fromPoints(pieces[i].vertices, name));
  }
  return out;
}

ConvexDecomposition decomposeConvex(const TriangleMesh& mesh, const DecompositionParams& params) {
  const auto start = std::chrono::steady_clock::now();
  params.validate();
  if (mesh.triangles.size() > static_cast<std::size_t>(params.maxTriangles)) {
    throw std::invalid_argument("decomposeConvex: mesh " + detail::meshName(mesh) + " has " +
                                std::to_string(mesh.triangles.size()) + " triangles, more than maxTriangles (" +
                                std::to_string(params.maxTriangles) +
                                "); raise it (deepcheck decompose --max-triangles N) or simplify the mesh");
  }
  const CleanMesh clean = cleanMesh(mesh);
  ConvexDecomposition result;
  DecompositionReport& report = result.report;
  report.source = mesh.source;
  report.numTriangles = clean.inputTriangles;
  report.numVertices = clean.inputVertices;
  report.holesFilled = clean.holesFilled;
  report.duplicatesRemoved = clean.duplicatesRemoved;
  report.voidsRemoved = clean.voidsRemoved;
  report.numComponents = clean.numComponents;
  report.diagonal = clean.diagonal;
  report.targetConcavity = params.targetConcavity(clean.diagonal);
  report.meshClosed = clean.closed;
  report.meshVolume = clean.volume;

  Decomposer decomposer(clean, params, report.targetConcavity, detail::meshName(mesh));
  result.pieces = decomposer.run(&report);

  report.numPieces = static_cast<int>(result.pieces.size());
  report.concavityRelative = report.concavity / clean.diagonal;
  report.targetMet = report.concavity <= report.targetConcavity;
  report.piecesVolume = 0.0;
  report.maxPieceVertices = 0;
  for (const ConvexPiece& piece : result.pieces) {
    report.piecesVolume += piece.volume;
    report.maxPieceVertices = std::max(report.maxPieceVertices, static_cast<int>(piece.vertices.size()));
  }
  report.volumeRatio = report.meshClosed && report.meshVolume > 0.0 ? report.piecesVolume / report.meshVolume
                                                                    : std::numeric_limits<double>::quiet_NaN();
  report.decomposeMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  report.milliseconds = report.decomposeMilliseconds;
  report.warning = targetWarning(report, result.pieces);
  return result;
}

std::string targetWarning(const DecompositionReport& report, const std::vector<ConvexPiece>& pieces) {
  int above = 0;
  double worst = 0.0;
  for (const ConvexPiece& piece : pieces) {
    above += piece.concavity > report.targetConcavity ? 1 : 0;
    worst = std::max(worst, piece.concavity);
  }
  if (above == 0) return "";
  using detail::roundedNumber;
  return "decomposition of " + detail::meshName(report.source) + " misses its target: " + std::to_string(above) +
         " of " + std::to_string(pieces.size()) + " pieces end up to " + roundedNumber(worst) +
         " m outside the mesh (" + roundedNumber(100.0 * worst / report.diagonal) + "% of its diagonal), target " +
         roundedNumber(report.targetConcavity) + " m; more pieces (maxPieces) or vertices per piece " +
         "(maxVerticesPerPiece) may meet it";
}

bool pieceContains(const ConvexPiece& piece, const Vector3d& point, double tolerance) {
  if (piece.volume > 0.0 && !piece.triangles.empty()) {
    for (const auto& t : piece.triangles) {
      const Vector3d& a = piece.vertices[t[0]];
      const Vector3d n = (piece.vertices[t[1]] - a).cross(piece.vertices[t[2]] - a);
      const double length = n.norm();
      if (!(length > 0.0)) continue;
      if (n.dot(point - a) / length > tolerance) return false;
    }
    return true;
  }
  // Flat or lower-dimensional: distance to the polygon, segment or point.
  double best = kInf;
  for (const auto& t : piece.triangles) {
    const Vector3d q =
        detail::closestPointOnTriangle(point, piece.vertices[t[0]], piece.vertices[t[1]], piece.vertices[t[2]]);
    best = std::min(best, (q - point).norm());
  }
  if (piece.triangles.empty() && !piece.vertices.empty()) {
    const Vector3d& a = piece.vertices.front();
    const Vector3d& b = piece.vertices.back();
    best = (detail::closestPointOnTriangle(point, a, b, b) - point).norm();
  }
  return best <= tolerance;
}

}  // namespace deepcheck::decomposition
