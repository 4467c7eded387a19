#pragma once
// deepcheck::checker in one include: the collision world (robot, scenes and obstacles as posed
// convex pieces) and its isFree / signed-distance / gradient queries, with their tolerances; the
// body-level signed distance (body_distance.h); the broad-phase extension point (broad_phase.h).
// The FCL reference backend (deepcheck/fcl_reference/fcl_backend.h) is not included: it belongs to the
// reference target.

#include "deepcheck/checker/body_distance.h"
#include "deepcheck/checker/broad_phase.h"
#include "deepcheck/checker/tolerances.h"
#include "deepcheck/checker/world.h"
