#pragma once
// Body-level signed distance in the world (World::bodySignedDistance, world_body_distance.cpp).
//
// World::signedDistance minimizes over pairs of convex pieces, so where a link overlaps several
// pieces of one body its depth and direction are the deepest PAIR's: a box pressed into a slab
// made of two touching boxes reads the depth into one of them and points sideways, into the other.
// bodySignedDistance measures two whole bodies, each the union of its pieces, with
// geometry::bodySignedDistance (deep/body_depth.h): overlapping, -distance is the length of the
// shortest translation of B after which no piece of A overlaps a piece of B.
//
// Bodies. A (BodyRef `a`): a robot link (its own pieces, not its attached objects) or an attached
// object (BodyRef::Kind::Attached, its pieces only). B (`b`): a robot link, an attached object, a
// scene link (its pieces the reach filter kept, as every query uses) or an obstacle (every piece of
// that id; a planning-scene object of several shapes is several obstacles, "<id>/<k>": one body
// of several pieces is a scene link with several collision elements, or a mesh obstacle
// decomposed into pieces). The pair is measured as named: allowed collisions do not apply.
//
// Contract: Contact as World::signedDistance gives it (world.h): normal unit from A towards B,
// pointB - pointA = distance * normal in the world frame; translating B by -distance * normal
// (or A by +distance * normal) makes the bodies touch; linkA the link of A (carrying it when
// attached), bodyB and the names; the gradient, when asked, is normal^T (J_B(pointB) -
// J_A(pointA)) with the witnesses fixed on their links (only links move).
//
// Rounded pieces. A sphere or capsule piece (radius > 0) has no polytope Minkowski difference, so
// the body depth cannot take it. Rule: when either body has a piece with a radius, the answer is
// the pairwise one, the minimum over all piece pairs of geometry::signedDistance (what
// World::signedDistance reports for that body pair), and BodyContact::method is Pairwise.

#include "deepcheck/checker/world.h"
#include "deepcheck/geometry/body_depth.h"

#include <Eigen/Core>

namespace deepcheck::checker {

/// Which answer a World::BodyContact holds (body_distance.h: rounded pieces).
enum class BodyDistanceMethod {
  Body,      ///< geometry::bodySignedDistance of the two unions
  Pairwise,  ///< a piece has a radius: the minimum over piece pairs
};
const char* toString(BodyDistanceMethod m);

struct World::BodyDistanceOptions {
  /// Also compute Contact::gradient (numVariables entries).
  bool gradient = false;
  /// The body query's options (its pairwise queries' options in depth.pair also serve the
  /// Pairwise method).
  geometry::BodyDepthOptions depth;
};

struct World::BodyContact {
  /// The answer. contact.status: Separated (apart, GJK converged), Penetrating (overlapping and
  /// certified: body status Certified, or a converged pairwise depth), else NotConverged (a valid
  /// separating translation whose depth is an upper bound).
  Contact contact;
  BodyDistanceMethod method = BodyDistanceMethod::Body;
  /// Body method: the body query's status and bracket on the depth (geometry::BodySignedDistanceResult).
  /// Pairwise method: Separated, or Certified when the pairwise depth converged (PairNotCertified
  /// when not), the bracket -distance twice.
  geometry::BodyDepthStatus depthStatus = geometry::BodyDepthStatus::Separated;
  double depthLower = 0.0;
  double depthUpper = 0.0;
  int overlappingPairs = 0;  ///< piece pairs with a negative signed distance
  /// The deepest pair's depth (0 when none overlaps) and normal: the pairwise answer, to compare.
  double pairDepth = 0.0;
  Eigen::Vector3d pairNormal = Eigen::Vector3d::UnitZ();
};

}  // namespace deepcheck::checker
