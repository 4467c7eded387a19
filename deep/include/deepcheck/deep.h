#pragma once
// deepcheck::deep in one include: convex polytopes (and the Qhull wrapper they are built with),
// GJK, the DEEP penetration depth and the signed distance between convex shapes, with their
// tolerances and the caller-owned scratch spaces. The exact reference penetration
// depth (deepcheck/deep/exact.h) is not included: it is a test and benchmark reference.

#include "deepcheck/deep/closest_point.h"
#include "deepcheck/deep/deep.h"
#include "deepcheck/deep/gjk.h"
#include "deepcheck/deep/pair_frame.h"
#include "deepcheck/deep/polytope.h"
#include "deepcheck/deep/qhull_hull.h"
#include "deepcheck/deep/signed_distance.h"
#include "deepcheck/deep/tolerances.h"
#include "deepcheck/deep/walk_scratch.h"
