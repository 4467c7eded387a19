// FCL 0.7 methods of the benchmark (see pd_peers.h).

#include "pd_peers.h"

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <iostream>
#include <limits>

namespace deepcheck::bench {
namespace {

/// fcl::Convex of every shape of a family: the hull's vertices (in the shape's own frame) and
/// its faces, coplanar facets merged into polygons, counter-clockwise seen from outside.
std::vector<std::shared_ptr<fcl::Convexd>> makeConvexes(const Family& f) {
  std::vector<std::shared_ptr<fcl::Convexd>> out;
  for (const geometry::ConvexPolytope& P : f.shapes) {
    auto vertices = std::make_shared<std::vector<fcl::Vector3d>>(P.vertices().begin(), P.vertices().end());
    auto faces = std::make_shared<std::vector<int>>();
    for (int face = 0; face < P.numFaces(); ++face) {
      const geometry::IndexRange ring = P.faceVertices(face);
      faces->push_back(ring.size());
      faces->insert(faces->end(), ring.begin(), ring.end());
    }
    out.push_back(std::make_shared<fcl::Convexd>(vertices, P.numFaces(), faces));
  }
  return out;
}

class FclMethod : public Method {
 public:
  FclMethod(fcl::GJKSolverType solver, bool distance) : solver_(solver), distance_(distance) {}

  std::string name() const override {
    return std::string("fcl_") + (solver_ == fcl::GST_LIBCCD ? "ccd" : "indep") +
           (distance_ ? "_distance" : "_collide");
  }

  void beginFamily(const Family& f) override {
    convexes_ = makeConvexes(f);
    unsafe_ = 0;
    lastSkipped_ = -1;
  }
  void endFamily() override {
    convexes_.clear();
    if (unsafe_ > 0)
      std::cerr << "  " << name() << ": " << unsafe_
                << " queries skipped (counted as failed, not timed): FCL 0.7 would abort"
                << " on an assertion (distance-inl.h: no contact of positive depth after a colliding GJK)\n";
  }

  /// fcl::distance with GST_INDEP and signed distance, on a pair its GJK finds colliding, calls
  /// fcl::collide for the depth and asserts that some contact has a positive depth; FCL's own
  /// EPA often returns non-positive depths, and the assertion (live in Debian's libfcl) aborts
  /// the process. That collide call is repeated here, untimed, and the query skipped when it
  /// would abort. Pairs separated by more than 1e-6 L are always run (GJK ends before collide).
  void beforeRun(const Family& f, int qi) override {
    skip_ = false;
    if (!(distance_ && solver_ == fcl::GST_INDEP)) return;
    const Query& q = f.queries[qi];
    if (q.exact && q.exact->distance > 1e-6 * f.pairScale(q)) return;
    fcl::CollisionRequestd request(1, true);
    request.gjk_solver_type = solver_;
    fcl::CollisionResultd result;
    fcl::collide(convexes_[q.a].get(), q.X_WA, convexes_[q.b].get(), q.X_WB, request, result);
    bool positive = false;
    for (std::size_t i = 0; i < result.numContacts(); ++i)
      positive = positive || result.getContact(i).penetration_depth > std::numeric_limits<double>::min();
    skip_ = !positive;
  }

  Answer run(const Family& f, int qi) override {
    const Query& q = f.queries[qi];
    const fcl::Convexd* a = convexes_[q.a].get();
    const fcl::Convexd* b = convexes_[q.b].get();
    if (skip_) {
      if (qi != lastSkipped_) ++unsafe_;
      lastSkipped_ = qi;
      return {Answer::Kind::Skipped, std::numeric_limits<double>::quiet_NaN()};
    }
    if (distance_) {
      fcl::DistanceRequestd request;
      request.enable_signed_distance = true;
      request.gjk_solver_type = solver_;
      fcl::DistanceResultd result;
      fcl::distance(a, q.X_WA, b, q.X_WB, request, result);
      return {Answer::Kind::SignedDistance, result.min_distance};
    }
    fcl::CollisionRequestd request(1, true);
    request.gjk_solver_type = solver_;
    fcl::CollisionResultd result;
    fcl::collide(a, q.X_WA, b, q.X_WB, request, result);
    if (!result.isCollision()) return {Answer::Kind::NoContact, 0.0};
    double depth = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < result.numContacts(); ++i)
      depth = std::max(depth, result.getContact(i).penetration_depth);
    if (result.numContacts() == 0) return {Answer::Kind::Failed, std::numeric_limits<double>::quiet_NaN()};
    return {Answer::Kind::SignedDistance, -depth};
  }

 private:
  fcl::GJKSolverType solver_;
  bool distance_;
  std::vector<std::shared_ptr<fcl::Convexd>> convexes_;
  bool skip_ = false;
  long unsafe_ = 0;
  int lastSkipped_ = -1;
};

}  // namespace

std::vector<std::unique_ptr<Method>> makeFclMethods() {
  std::vector<std::unique_ptr<Method>> m;
  m.push_back(std::make_unique<FclMethod>(fcl::GST_LIBCCD, false));
  m.push_back(std::make_unique<FclMethod>(fcl::GST_LIBCCD, true));
  m.push_back(std::make_unique<FclMethod>(fcl::GST_INDEP, false));
  m.push_back(std::make_unique<FclMethod>(fcl::GST_INDEP, true));
  return m;
}

}  // namespace deepcheck::bench
