#pragma once
// deepcheck::geometry in one include: convex polytopes (and the Qhull wrapper they are built with),
// GJK distance, the signed distance between convex shapes with its penetration options, and the
// tolerances. The body depth (deepcheck/geometry/body_depth.h) and the exact reference signed
// distance (deepcheck/geometry/exact.h, a test and benchmark reference) have their own headers.
// Headers under deepcheck/geometry/internal/ are the library's own, not part of its interface.

#include "deepcheck/geometry/closest_point.h"
#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/geometry/penetration_options.h"
#include "deepcheck/geometry/polytope.h"
#include "deepcheck/geometry/qhull_hull.h"
#include "deepcheck/geometry/signed_distance.h"
#include "deepcheck/geometry/tolerances.h"
