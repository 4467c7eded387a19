// The project's methods (certified and DEEP's walk, warm and cold; GJK) and libccd called directly (see pd_methods.h).

#include "pd_methods.h"

#include "pd_peers.h"

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/signed_distance.h"

#include <ccd/ccd.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

namespace deepcheck::bench {
namespace {

using geometry::ConvexPolytope;

WalkStats walkOf(const geometry::SignedDistanceResult& r) {
  WalkStats w;
  w.valid = true;
  w.starts = r.walk.starts;
  w.hubs = r.walk.hubs;
  w.steps = r.walk.steps;
  w.localMinima = r.walk.localMinima;
  w.expansions = r.expansions;
  w.warm = r.walk.warm;
  w.notConverged = r.status == geometry::SignedDistanceStatus::NotConverged;
  return w;
}

geometry::PenetrationOptions optionsFor(geometry::PenetrationMethod method) {
  geometry::PenetrationOptions o;
  o.method = method;
  return o;
}

const char* prefixOf(geometry::PenetrationMethod method) {
  return method == geometry::PenetrationMethod::CertifiedExpansion ? "certified" : "deep";
}

/// signedDistance() with a PairCache primed as pd_families.h describes (previous step, or the
/// same pair at a nearby pose): the Gauss-map walk ("deep_warm") or the certified method
/// ("certified_warm"). The methods' scratch space is the benchmark method's own, reused.
class Warm : public Method {
 public:
  explicit Warm(geometry::PenetrationMethod method)
      : options_(optionsFor(method)), name_(std::string(prefixOf(method)) + "_warm") {}
  std::string name() const override { return name_; }

  void beginFamily(const Family& f) override {
    primed_.assign(f.queries.size(), geometry::PairCache{});
    geometry::PairCache carried;
    carried.scratch = &scratch_;
    for (std::size_t i = 0; i < f.queries.size(); ++i) {
      const Query& q = f.queries[i];
      const ConvexPolytope& A = f.shapes[q.a];
      const ConvexPolytope& B = f.shapes[q.b];
      if (f.sequence) {
        if (i == 0 || q.a != f.queries[i - 1].a || q.b != f.queries[i - 1].b) carried.reset();
        primed_[i] = carried;
        geometry::signedDistance(A, q.X_WA, B, q.X_WB, &carried, options_);
      } else {
        geometry::PairCache c;
        c.scratch = &scratch_;
        geometry::signedDistance(A, q.X_WA, B, q.primeB->iso(), &c, options_);
        primed_[i] = c;
      }
    }
    working_ = primed_;
  }

  Answer run(const Family& f, int qi) override {
    const Query& q = f.queries[qi];
    last_ = geometry::signedDistance(f.shapes[q.a], q.X_WA, f.shapes[q.b], q.X_WB, &working_[qi], options_);
    return {Answer::Kind::SignedDistance, last_.distance};
  }
  void afterRun(const Family&, int q) override { working_[q] = primed_[q]; }

  WalkStats lastWalk() const override { return walkOf(last_); }
  void endFamily() override {
    primed_.clear();
    working_.clear();
  }

 private:
  geometry::PenetrationOptions options_;
  std::string name_;
  geometry::PenetrationScratch scratch_;
  std::vector<geometry::PairCache> primed_;   // each query's cache as primed, kept unchanged
  std::vector<geometry::PairCache> working_;  // the caches the timed queries use, reset after each
  geometry::SignedDistanceResult last_;
};

/// Every query cold: DEEP's walk with all restarts ("deep_cold") or the certified method
/// ("certified_cold"), each with a cache that is reset before the query (it only carries the
/// certified method's scratch surface).
class Cold : public Method {
 public:
  explicit Cold(geometry::PenetrationMethod method) : options_(optionsFor(method)), prefix_(prefixOf(method)) {
    cache_.scratch = &scratch_;
  }
  std::string name() const override { return prefix_ + "_cold"; }
  void beginFamily(const Family&) override {}
  void beforeRun(const Family&, int) override { cache_.reset(); }
  Answer run(const Family& f, int qi) override {
    const Query& q = f.queries[qi];
    last_ = geometry::signedDistance(f.shapes[q.a], q.X_WA, f.shapes[q.b], q.X_WB, &cache_, options_);
    return {Answer::Kind::SignedDistance, last_.distance};
  }
  WalkStats lastWalk() const override { return walkOf(last_); }

 private:
  geometry::PenetrationOptions options_;
  std::string prefix_;
  geometry::PenetrationScratch scratch_;
  geometry::PairCache cache_;
  geometry::SignedDistanceResult last_;
};

/// The project's GJK distance, cold, on separated pairs only.
class ProjectGjk : public Method {
 public:
  std::string name() const override { return "gjk"; }
  bool separatedOnly() const override { return true; }
  void beginFamily(const Family&) override {}
  Answer run(const Family& f, int qi) override {
    const Query& q = f.queries[qi];
    const ConvexPolytope& A = f.shapes[q.a];
    const ConvexPolytope& B = f.shapes[q.b];
    const geometry::GjkResult g = geometry::gjkDistance(A, B, geometry::PairFrame::make(A, q.X_WA, B, q.X_WB));
    const bool apart = g.status == geometry::GjkStatus::Separated || g.status == geometry::GjkStatus::MaxIterations;
    return {Answer::Kind::SignedDistance, apart ? g.distance : 0.0};
  }
};

// ---- libccd, called directly ---------------------------------------------------------------

/// A polytope posed in the pair frame P of the query (A's centroid frame), so libccd works in
/// coordinates of the size of the shapes, as DEEP does. `hint` is the last support vertex.
struct CcdShape {
  const ConvexPolytope* polytope = nullptr;
  const geometry::PairFrame* frame = nullptr;  ///< null for A (identity), the pair frame for B
  int hint = 0;
};

void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  // libccd passes const objects; the hint is scratch state of this query only.
  auto* s = static_cast<CcdShape*>(const_cast<void*>(obj));
  const Eigen::Vector3d d_P(dir->v[0], dir->v[1], dir->v[2]);
  Eigen::Vector3d p_P;
  if (s->frame == nullptr) {
    s->hint = s->polytope->support(d_P, s->hint);
    p_P = s->polytope->localVertex(s->hint);
  } else {
    s->hint = s->polytope->support(s->frame->toB(d_P), s->hint);
    p_P = s->frame->vertexB(*s->polytope, s->hint);
  }
  out->v[0] = p_P.x();
  out->v[1] = p_P.y();
  out->v[2] = p_P.z();
}

void ccdCenter(const void* obj, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdShape*>(obj);
  const Eigen::Vector3d c = s->frame == nullptr ? Eigen::Vector3d::Zero() : s->frame->t;
  out->v[0] = c.x();
  out->v[1] = c.y();
  out->v[2] = c.z();
}

/// libccd's ccdGJKPenetration (GJK + EPA) or ccdMPRPenetration. Tolerances: libccd's defaults
/// (epa and mpr 1e-4, dist 1e-6, meant for shapes of size ~1) multiplied by the pair's size L,
/// so that the scale families do not fail on absolute tolerances; max_iterations 1000 (the
/// default is unlimited).
class CcdPenetration : public Method {
 public:
  explicit CcdPenetration(bool mpr) : mpr_(mpr) {}
  std::string name() const override { return mpr_ ? "ccd_mpr" : "ccd_gjk_epa"; }
  void beginFamily(const Family&) override {}
  Answer run(const Family& f, int qi) override {
    const Query& q = f.queries[qi];
    const ConvexPolytope& A = f.shapes[q.a];
    const ConvexPolytope& B = f.shapes[q.b];
    const geometry::PairFrame frame = geometry::PairFrame::make(A, q.X_WA, B, q.X_WB);
    const double L = std::max(A.boundingRadius(), B.boundingRadius());
    CcdShape a{&A, nullptr, 0};
    CcdShape b{&B, &frame, 0};
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = ccdSupport;
    ccd.support2 = ccdSupport;
    ccd.center1 = ccdCenter;
    ccd.center2 = ccdCenter;
    ccd.max_iterations = 1000;
    ccd.epa_tolerance = 1e-4 * L;
    ccd.mpr_tolerance = 1e-4 * L;
    ccd.dist_tolerance = 1e-6 * L;
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    const int status = mpr_ ? ccdMPRPenetration(&a, &b, &ccd, &depth, &dir, &pos)
                            : ccdGJKPenetration(&a, &b, &ccd, &depth, &dir, &pos);
    if (status == -1) return {Answer::Kind::NoContact, 0.0};
    if (status != 0) return {Answer::Kind::Failed, std::numeric_limits<double>::quiet_NaN()};
    return {Answer::Kind::SignedDistance, -depth};
  }

 private:
  bool mpr_;
};

}  // namespace

std::vector<std::unique_ptr<Method>> makeMethods() {
  std::vector<std::unique_ptr<Method>> m;
  m.push_back(std::make_unique<Warm>(geometry::PenetrationMethod::CertifiedExpansion));
  m.push_back(std::make_unique<Cold>(geometry::PenetrationMethod::CertifiedExpansion));
  m.push_back(std::make_unique<Warm>(geometry::PenetrationMethod::GaussMapWalk));
  m.push_back(std::make_unique<Cold>(geometry::PenetrationMethod::GaussMapWalk));
  m.push_back(std::make_unique<ProjectGjk>());
  for (auto& peer : makeFclMethods()) m.push_back(std::move(peer));
  m.push_back(std::make_unique<CcdPenetration>(false));
  m.push_back(std::make_unique<CcdPenetration>(true));
  for (auto& peer : makeBulletMethods()) m.push_back(std::move(peer));
  return m;
}

}  // namespace deepcheck::bench
