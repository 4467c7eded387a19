#include "external_broad_phase.h"

#include <atomic>
#include <stdexcept>
#include <string>

namespace deepcheck::checker::detail {
namespace {

std::atomic<ExternalPieceTreeFactory> fclTreeFactory{nullptr};

}  // namespace

void setExternalBroadPhase(BroadPhase broadPhase, ExternalPieceTreeFactory factory) {
  if (broadPhase != BroadPhase::FclTree) {
    throw std::invalid_argument(std::string("setExternalBroadPhase: broad phase ") + toString(broadPhase) +
                                " is built into the checker");
  }
  fclTreeFactory.store(factory);
}

std::shared_ptr<const ExternalPieceTree> makeExternalPieceTree(BroadPhase broadPhase, const std::vector<Aabb>& boxes) {
  const ExternalPieceTreeFactory factory = broadPhase == BroadPhase::FclTree ? fclTreeFactory.load() : nullptr;
  if (factory == nullptr) {
    throw std::invalid_argument(std::string("World: broad phase ") + toString(broadPhase) +
                                " is provided by deepcheck::fcl_reference: link it and call "
                                "deepcheck::fcl_reference::enableFclBroadPhase() first");
  }
  if (boxes.empty()) return nullptr;
  return factory(boxes);
}

}  // namespace deepcheck::checker::detail
