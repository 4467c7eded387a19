// PenetrationScratch (signed_distance.h): out of line, where the scratch space's types are
// complete.

#include "deepcheck/geometry/internal/expansion_surface.h"
#include "deepcheck/geometry/internal/walk_scratch.h"
#include "deepcheck/geometry/signed_distance.h"

namespace deepcheck::geometry {

PenetrationScratch::PenetrationScratch()
    : surface_(std::make_unique<detail::ExpansionSurface>()), walk_(std::make_unique<detail::WalkScratch>()) {}
PenetrationScratch::~PenetrationScratch() = default;
PenetrationScratch::PenetrationScratch(PenetrationScratch&&) noexcept = default;
PenetrationScratch& PenetrationScratch::operator=(PenetrationScratch&&) noexcept = default;

}  // namespace deepcheck::geometry
