#pragma once
// deepcheck::planners in one include: the OMPL plug-in (state validity checker with clearance,
// certified and clearance motion validators and their link speed bound, push-out repair and valid state sampler,
// clearance objectives, path tools, planner factory and the one-call setup).
// The FCL reference checker (deepcheck/fcl_reference/fcl_validity_checker.h, target deepcheck::fcl_reference) is not
// included: it belongs to the reference target.

#include "deepcheck/planners/certified_motion_memo.h"
#include "deepcheck/planners/certified_motion_validator.h"
#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/motion_validator.h"
#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/valid_state_sampler.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/planners/validity_checker.h"
