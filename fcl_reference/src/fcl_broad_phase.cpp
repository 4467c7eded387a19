#include "deepcheck/fcl_reference/fcl_broad_phase.h"

#include "deepcheck/checker/broad_phase.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace deepcheck::fcl_reference {
namespace {

using checker::Aabb;

fcl::AABBd toFcl(const Aabb& b) { return fcl::AABBd(b.lo, b.hi); }

/// A collision object whose world box is set directly (the manager reads nothing else).
struct BoxObject : fcl::CollisionObjectd {
  using fcl::CollisionObjectd::CollisionObjectd;
  void setBox(const Aabb& b) { aabb = toFcl(b); }
};

struct OverlapData {
  const std::function<bool(int)>* visit;
};

bool overlapCallback(fcl::CollisionObjectd* item, fcl::CollisionObjectd* /*query*/, void* data) {
  auto* d = static_cast<OverlapData*>(data);
  const int index = static_cast<int>(reinterpret_cast<std::intptr_t>(item->getUserData()));
  return (*d->visit)(index);
}

struct NearData {
  const std::function<double()>* bound;
  const std::function<void(int, double)>* visit;
  const Eigen::Vector3d* center;
  double radius;
  const std::vector<Aabb>* boxes;
};

bool nearCallback(fcl::CollisionObjectd* item, fcl::CollisionObjectd* /*query*/, void* data, double& dist) {
  auto* d = static_cast<NearData*>(data);
  const int index = static_cast<int>(reinterpret_cast<std::intptr_t>(item->getUserData()));
  const double lowerBound = (*d->boxes)[index].signedDistance(*d->center) - d->radius;
  if (lowerBound < (*d->bound)()) (*d->visit)(index, lowerBound);
  // FCL skips a node whose box is at least `dist` from the query's box, and overlapping boxes are
  // at distance 0: a bound at or below zero (a penetration found) must still visit them all.
  dist = std::max((*d->bound)(), std::numeric_limits<double>::min());
  return false;
}

class FclPieceTree : public checker::PieceTree {
 public:
  explicit FclPieceTree(const std::vector<Aabb>& boxes);
  FclPieceTree(const FclPieceTree&) = delete;
  FclPieceTree& operator=(const FclPieceTree&) = delete;

  bool visitOverlapping(const Aabb& query, const std::function<bool(int)>& visit) const override;
  void visitNear(const Eigen::Vector3d& c, double r, const std::function<double()>& bound,
                 const std::function<void(int, double)>& visit) const override;

 private:
  struct Impl {
    std::shared_ptr<fcl::CollisionGeometryd> unitBox = std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0);
    std::vector<std::unique_ptr<BoxObject>> objects;
    std::vector<Aabb> boxes;
    fcl::DynamicAABBTreeCollisionManagerd manager;
  };
  std::unique_ptr<Impl> impl_;
};

FclPieceTree::FclPieceTree(const std::vector<Aabb>& boxes) : impl_(std::make_unique<Impl>()) {
  impl_->boxes = boxes;
  std::vector<fcl::CollisionObjectd*> raw;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    auto object = std::make_unique<BoxObject>(impl_->unitBox);
    object->setBox(boxes[i]);
    object->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(i)));
    raw.push_back(object.get());
    impl_->objects.push_back(std::move(object));
  }
  impl_->manager.registerObjects(raw);
  impl_->manager.setup();
}

bool FclPieceTree::visitOverlapping(const Aabb& query, const std::function<bool(int)>& visit) const {
  BoxObject object(impl_->unitBox);
  object.setBox(query);
  OverlapData data{&visit};
  bool stopped = false;
  // The manager stops when the callback returns true; remember whether it did.
  const std::function<bool(int)> wrapped = [&](int i) { return stopped = visit(i); };
  data.visit = &wrapped;
  impl_->manager.collide(&object, &data, overlapCallback);
  return stopped;
}

void FclPieceTree::visitNear(const Eigen::Vector3d& c, double r, const std::function<double()>& bound,
                             const std::function<void(int, double)>& visit) const {
  BoxObject object(impl_->unitBox);
  object.setBox(Aabb::ofSphere(c, r));
  NearData data{&bound, &visit, &c, r, &impl_->boxes};
  impl_->manager.distance(&object, &data, nearCallback);
}

class FclPieceTreeFactory : public checker::PieceTreeFactory {
 public:
  std::string name() const override { return "fcl-dynamic-aabb-tree"; }
  std::shared_ptr<const checker::PieceTree> build(const std::vector<Aabb>& boxes) const override {
    return std::make_shared<const FclPieceTree>(boxes);
  }
};

}  // namespace

std::shared_ptr<const checker::PieceTreeFactory> fclBroadPhase() {
  static const auto factory = std::make_shared<const FclPieceTreeFactory>();
  return factory;
}

}  // namespace deepcheck::fcl_reference
