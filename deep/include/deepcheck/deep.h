#pragma once
// deepcheck::deep in one include: convex polytopes (and the Qhull wrapper they are built with),
// GJK distance, the signed distance between convex shapes with its penetration options, and the
// tolerances. The body depth (deepcheck/deep/body_depth.h) and the exact reference signed
// distance (deepcheck/deep/exact.h, a test and benchmark reference) have their own headers.
// Headers under deepcheck/deep/internal/ are the library's own, not part of its interface.

#include "deepcheck/deep/closest_point.h"
#include "deepcheck/deep/gjk.h"
#include "deepcheck/deep/pair_frame.h"
#include "deepcheck/deep/penetration_options.h"
#include "deepcheck/deep/polytope.h"
#include "deepcheck/deep/qhull_hull.h"
#include "deepcheck/deep/signed_distance.h"
#include "deepcheck/deep/tolerances.h"
