#pragma once
// The methods the penetration-depth benchmark compares, behind one small interface.
//
// Every method answers a query with a signed distance estimate (negative: penetration depth),
// or, for methods that only compute penetration (collision with contacts, EPA/MPR), with
// "no contact". Everything a method needs per shape (FCL Convex, Bullet hull, ...) is built in
// beginFamily(), outside the timed region; run() is the timed call and contains only what a
// user would do per query (request/result objects included).
//
// Support functions, per method (they decide much of the cost on large hulls):
//   deep_*, gjk, ccd_*   the project's ConvexPolytope::support: hill climbing over the vertex
//                        graph from a hint (the last support vertex), brute force up to 16
//                        vertices. libccd is called directly with that support function.
//   fcl_*                fcl::Convex::findExtremeVertex: hill climbing over the vertex graph
//                        from vertex 0 (brute force up to 32 vertices), FCL's own.
//   bullet_*             btConvexHullShape: brute force over all vertices (SIMD dot products),
//                        Bullet's own.

#include "pd_families.h"

#include <memory>
#include <string>
#include <vector>

namespace deepcheck::bench {

struct Answer {
  enum class Kind {
    SignedDistance,  ///< sd holds the method's signed distance (may be NaN if it produced one)
    NoContact,       ///< a penetration-only method reported no overlap (no distance given)
    Failed,          ///< the method reported failure or threw
    Skipped,         ///< not run: the call would abort the process (counted as failed, not timed)
  } kind = Kind::Failed;
  double sd = 0.0;
};

/// Walk statistics of a DEEP query (copied from geometry::WalkStats), the certified expansion's support
/// points added to its surface, and whether it converged.
struct WalkStats {
  bool valid = false;
  int starts = 0, hubs = 0, steps = 0, localMinima = 0, expansions = 0;
  bool warm = false;
  bool notConverged = false;
};

class Method {
 public:
  virtual ~Method() = default;
  virtual std::string name() const = 0;
  /// Runs only on pairs whose exact signed distance is positive (GJK distance).
  virtual bool separatedOnly() const { return false; }
  /// Untimed preparation for a family (per-shape data, warm-start priming).
  virtual void beginFamily(const Family& family) = 0;
  /// Untimed, before every timed run of query q.
  virtual void beforeRun(const Family& /*family*/, int /*q*/) {}
  /// Untimed, after every timed run of query q (restores warm-start state for the next run, so
  /// that nothing of the pair is touched just before its next timed run).
  virtual void afterRun(const Family& /*family*/, int /*q*/) {}
  /// The timed query.
  virtual Answer run(const Family& family, int q) = 0;
  /// Statistics of the last run (DEEP only).
  virtual WalkStats lastWalk() const { return {}; }
  virtual void endFamily() {}
};

/// All methods of the benchmark, in table order, except the exact reference (timed separately).
std::vector<std::unique_ptr<Method>> makeMethods();

}  // namespace deepcheck::bench
