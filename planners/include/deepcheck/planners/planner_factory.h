#pragma once
// OMPL geometric planners by name, for the tool, the examples and the benchmark.
//
// Names (case-insensitive; "*" may be written "star"): RRTConnect, RRT, RRT*, InformedRRT*,
// BIT*, PRM, PRM*, LazyPRM, LazyPRM*, KPIECE1, BKPIECE1, EST, BiEST, SBL, FMT, TRRT. The name a
// planner made here gives itself (Planner::getName: "RRTstar", "kBITstar") is accepted too.
// Every planner gets OMPL's default parameters.

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>

#include <string>
#include <vector>

namespace deepcheck::planners {

/// The canonical names accepted by makePlanner, in the order above.
std::vector<std::string> plannerNames();

/// The canonical name (as plannerNames() spells it) of `name`. Throws std::invalid_argument naming
/// `name` and listing the known ones.
std::string plannerName(const std::string& name);

/// A new planner. Throws std::invalid_argument naming `name` and listing the known ones.
ompl::base::PlannerPtr makePlanner(const std::string& name, const ompl::base::SpaceInformationPtr& si);

/// True for the planners that optimize a cost (RRT*, InformedRRT*, BIT*, PRM*, LazyPRM*, FMT);
/// false for an unknown name.
bool isOptimizingPlanner(const std::string& name);

}  // namespace deepcheck::planners
