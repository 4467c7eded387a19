// The certified method's start without GJK, for pairs known to overlap (signed_distance.cpp asks
// for it when the shapes' inscribed balls overlap). The supports of M = B - A in the twelve probe
// directions, joined as the icosahedron's faces, start the expanding surface in place of GJK's
// simplex when they form a convex surface strictly around the origin; the best-first expansion
// then runs as from any start. Twelve supports spread over all directions leave fewer expansions
// than GJK's four points, and A's side of each is read from its table (detail::probeSupport), so
// only B climbs.

#include "deepcheck/geometry/internal/certified.h"
#include "deepcheck/geometry/tolerances.h"

#include "probe_icosahedron.h"

#include <algorithm>

namespace deepcheck::geometry::detail {

bool certifiedFromProbes(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                         ExpansionSurface& surface, const CertifiedOptions& options, CertifiedResult& result) {
  const probe::Icosahedron& ico = probe::icosahedron();
  ExpansionSurface::Vertex w[probe::kDirections];
  int b = 0;
  for (int i = 0; i < probe::kDirections; ++i) {
    const int a = probeSupport(A, ico.opposite[i]);  // A's vertex lowest along direction i
    b = B.support(frame.toB(ico.direction[i]), b);
    w[i] = {frame.vertexB(B, b) - A.localVertex(a), a, b};
    for (int j = 0; j < i; ++j)
      if (w[j].a == a && w[j].b == b) return false;  // two directions tie: the surface would pinch
  }
  const double L = pairLengthScale(A, B, frame);
  if (!surface.startConvex(w, probe::kDirections, ico.face, ico.adj, probe::kFaces, tol::kFlatRelative * L))
    return false;
  result = certifiedFromSurface(A, B, frame, surface, options);
  return true;
}

}  // namespace deepcheck::geometry::detail
