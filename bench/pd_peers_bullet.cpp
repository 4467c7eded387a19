// Bullet methods of the benchmark (see pd_peers.h). Compiled with BT_USE_DOUBLE_PRECISION and
// linked to Bullet's float64 libraries.

#include "pd_peers.h"

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <limits>

#ifndef BT_USE_DOUBLE_PRECISION
#error "the Bullet peer must be built in double precision (bullet-float64)"
#endif

namespace deepcheck::bench {
namespace {

btTransform toBullet(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  const Eigen::Vector3d& p = X.translation();
  return btTransform(btMatrix3x3(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)),
                     btVector3(p.x(), p.y(), p.z()));
}

class BulletMethod : public Method {
 public:
  explicit BulletMethod(bool signedDistance) : signed_(signedDistance) {}
  std::string name() const override { return signed_ ? "bullet_signed" : "bullet_penetration"; }

  void beginFamily(const Family& f) override {
    hulls_.clear();
    for (const geometry::ConvexPolytope& P : f.shapes) {
      auto hull = std::make_unique<btConvexHullShape>();
      for (const Eigen::Vector3d& v : P.vertices()) hull->addPoint(btVector3(v.x(), v.y(), v.z()), false);
      hull->recalcLocalAabb();
      hull->setMargin(0.0);  // no rounding: the exact hull, as every other method sees it
      hulls_.push_back(std::move(hull));
    }
  }
  void endFamily() override { hulls_.clear(); }

  Answer run(const Family& f, int qi) override {
    const Query& q = f.queries[qi];
    const btTransform XA = toBullet(q.X_WA);
    const btTransform XB = toBullet(q.X_WB);
    const Eigen::Vector3d c = q.X_WB * f.shapes[q.b].center() - q.X_WA * f.shapes[q.a].center();
    const btVector3 guess(c.x(), c.y(), c.z());
    btGjkEpaSolver2::sResults r;
    if (signed_) {
      const bool ok = btGjkEpaSolver2::SignedDistance(hulls_[q.a].get(), XA, hulls_[q.b].get(), XB, guess, r);
      if (!ok) return {Answer::Kind::Failed, std::numeric_limits<double>::quiet_NaN()};
      return {Answer::Kind::SignedDistance, r.distance};
    }
    const bool hit = btGjkEpaSolver2::Penetration(hulls_[q.a].get(), XA, hulls_[q.b].get(), XB, guess, r);
    if (hit) return {Answer::Kind::SignedDistance, r.distance};
    if (r.status == btGjkEpaSolver2::sResults::Separated) return {Answer::Kind::NoContact, 0.0};
    return {Answer::Kind::Failed, std::numeric_limits<double>::quiet_NaN()};
  }

 private:
  bool signed_;
  std::vector<std::unique_ptr<btConvexHullShape>> hulls_;
};

}  // namespace

std::vector<std::unique_ptr<Method>> makeBulletMethods() {
  std::vector<std::unique_ptr<Method>> m;
  m.push_back(std::make_unique<BulletMethod>(false));
  m.push_back(std::make_unique<BulletMethod>(true));
  return m;
}

}  // namespace deepcheck::bench
