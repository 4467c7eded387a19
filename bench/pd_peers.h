#pragma once
// Peer libraries behind the Method interface, each in its own translation unit (FCL's templates
// and Bullet's double-precision define stay out of the rest of the benchmark).

#include "pd_methods.h"

#include <memory>
#include <vector>

namespace deepcheck::bench {

/// FCL 0.7 on fcl::Convex built from the same hull (vertices and merged faces):
///   fcl_ccd_collide    fcl::collide with contacts, GST_LIBCCD (libccd MPR inside FCL);
///                      penetration depth = the largest contact depth
///   fcl_ccd_distance   fcl::distance with enable_signed_distance, GST_LIBCCD (GJK + EPA)
///   fcl_indep_collide  fcl::collide with contacts, GST_INDEP (FCL's own GJK + EPA)
///   fcl_indep_distance fcl::distance with enable_signed_distance, GST_INDEP
/// All with FCL's default tolerances.
std::vector<std::unique_ptr<Method>> makeFclMethods();

/// Bullet 3.24, double precision (libBulletCollision-float64), btConvexHullShape with margin 0:
///   bullet_penetration  btGjkEpaSolver2::Penetration
///   bullet_signed       btGjkEpaSolver2::SignedDistance
/// The initial guess is the centroid difference, as a caller without a cache would pass.
std::vector<std::unique_ptr<Method>> makeBulletMethods();

}  // namespace deepcheck::bench
