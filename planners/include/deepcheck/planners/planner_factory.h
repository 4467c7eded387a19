#pragma once
// OMPL geometric planners by name, for the tool, the examples and the benchmark.
//
// Names (case-insensitive; "*" may be written "star"): RRTConnect, RRT, RRT*, InformedRRT*,
// BIT*, PRM, PRM*, LazyPRM, LazyPRM*, KPIECE1, BKPIECE1, EST, BiEST, SBL, FMT, TRRT. The name a
// planner made here gives itself (Planner::getName: "RRTstar", "kBITstar") is accepted too.
// Every planner gets OMPL's default parameters, except the range of the planners that do not
// optimize a cost (RRTConnect, RRT, KPIECE1, ...): defaultRange(), 1.5 rad on the Panda
// instead of OMPL's 0.2 of the space's extent (2.7 rad). prepareForCostlyObjective changes RRT*'s
// neighbours and range for the clearance objective.

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

/// A new planner (the range of one that does not optimize: defaultRange). Throws
/// std::invalid_argument naming `name` and listing the known ones.
ompl::base::PlannerPtr makePlanner(const std::string& name, const ompl::base::SpaceInformationPtr& si);

/// The longest motion a tree planner that does not optimize adds in one step:
/// tol::kDefaultRangeFraction of the space's maximum extent.
double defaultRange(const ompl::base::SpaceInformation& si);

/// True for the planners that optimize a cost (RRT*, InformedRRT*, BIT*, PRM*, LazyPRM*, FMT);
/// false for an unknown name.
bool isOptimizingPlanner(const std::string& name);

/// Prepares `planner` for an objective whose motion costs are expensive (the clearance hinge of
/// objectives.h integrates distance queries along each motion). RRT* and InformedRRT* are switched
/// from k-nearest to radius neighbours: OMPL 1.5's k-nearest RRT* asks the cost of the motion to
/// k = 1.1 * 2^(d+1) e (1 + 1/d) ln(n) nodes for each new node (d joints, n nodes; 35.9 ln n for 2
/// joints, and more than the whole tree for 7 joints below ~10^4 nodes), those farther
/// than its range included, which it then never connects. The radius variant asks only the nodes
/// within min(range, r(n)); and since r(n) stays above OMPL's default range (0.2 of the extent:
/// 5.76 rad on a UR5) for the first ~10^4 nodes, a range that was not set is set to
/// tol::kCostlyObjectiveRangeFraction of the extent (1.15 rad on a UR5), which also bounds each
/// motion whose cost is integrated. A range the caller set is kept. BIT* and PRM* need nothing
/// here (BIT*'s informed sampling is the objective's, objectives.h). Other planners are left as
/// they are. Returns true when it changed the planner.
bool prepareForCostlyObjective(ompl::base::Planner& planner);

}  // namespace deepcheck::planners
