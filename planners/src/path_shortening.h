#pragma once
// One pass of path shortening for simplifySolutionChecked (setup.h): OMPL's vertex reduction,
// shortcuts, vertex reduction again and two rounds of B-spline smoothing, every change through the
// motion validator of the path's space information. OMPL's simplifyMax repeats such passes until
// nothing improves: slightly shorter paths for several times the time, so one pass is the default.
//
// With a CertifiedMotionValidator the smoothing is deepcheck's own (smoothCorners), for the same
// path with fewer tests: every vertex of a certified path is valid, so the validity test OMPL's
// smoothBSpline makes of the vertex before each corner is skipped, and a corner that would not
// move is not checked.

#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>

namespace deepcheck::planners {

void shortenPath(ompl::geometric::PathSimplifier& simplifier, ompl::geometric::PathGeometric& path);

}  // namespace deepcheck::planners
