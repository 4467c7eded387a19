#include "deepcheck/planners/planner_factory.h"

#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/vector_nearest.h"

#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>

namespace deepcheck::planners {

namespace {

namespace og = ompl::geometric;
using Maker = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)>;

template <class P>
Maker maker() {
  return [](const ompl::base::SpaceInformationPtr& si) { return std::make_shared<P>(si); };
}

/// OMPL's RRTConnect whose two trees find nearest neighbours with VectorNearest: made only on a
/// RealVectorStateSpace itself (not a subclass, whose distance may differ).
class VectorNearestRRTConnect : public og::RRTConnect {
 public:
  VectorNearestRRTConnect(const ompl::base::SpaceInformationPtr& si, unsigned dimension) : og::RRTConnect(si) {
    tStart_ = std::make_shared<VectorNearest<Motion*>>(dimension);
    tGoal_ = std::make_shared<VectorNearest<Motion*>>(dimension);
  }
};

Maker rrtConnect() {
  return [](const ompl::base::SpaceInformationPtr& si) -> ompl::base::PlannerPtr {
    const ompl::base::StateSpace& space = *si->getStateSpace();
    if (typeid(space) != typeid(ompl::base::RealVectorStateSpace)) return std::make_shared<og::RRTConnect>(si);
    return std::make_shared<VectorNearestRRTConnect>(si, space.getDimension());
  };
}

/// BIT* is k-nearest by default, and OMPL renames (with a warning) a k-nearest BIT* called
/// "BITstar" at setup: name it "kBITstar" from the start.
constexpr const char* kBitStarName = "kBITstar";
Maker bitStar() {
  return [](const ompl::base::SpaceInformationPtr& si) { return std::make_shared<og::BITstar>(si, kBitStarName); };
}

struct Entry {
  const char* name;
  bool optimizing;
  Maker make;
  /// The name the planner gives itself (Planner::getName) when it is not `name` written with
  /// "star".
  const char* omplName = nullptr;
};

const std::vector<Entry>& table() {
  static const std::vector<Entry> entries = {
      {"RRTConnect", false, rrtConnect()},
      {"RRT", false, maker<og::RRT>()},
      {"RRT*", true, maker<og::RRTstar>()},
      {"InformedRRT*", true, maker<og::InformedRRTstar>()},
      {"BIT*", true, bitStar(), kBitStarName},
      {"PRM", false, maker<og::PRM>()},
      {"PRM*", true, maker<og::PRMstar>()},
      {"LazyPRM", false, maker<og::LazyPRM>()},
      {"LazyPRM*", true, maker<og::LazyPRMstar>()},
      {"KPIECE1", false, maker<og::KPIECE1>()},
      {"BKPIECE1", false, maker<og::BKPIECE1>()},
      {"EST", false, maker<og::EST>()},
      {"BiEST", false, maker<og::BiEST>()},
      {"SBL", false, maker<og::SBL>()},
      {"FMT", true, maker<og::FMT>()},
      {"TRRT", false, maker<og::TRRT>()},
  };
  return entries;
}

/// Lower case, "star" for "*".
std::string canonical(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (c == '*') {
      out += "star";
    } else {
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  return out;
}

const Entry* find(const std::string& name) {
  const std::string key = canonical(name);
  for (const Entry& e : table()) {
    if (canonical(e.name) == key || (e.omplName != nullptr && canonical(e.omplName) == key)) return &e;
  }
  return nullptr;
}

/// The entry of `name`; std::invalid_argument naming it and listing the known ones otherwise.
const Entry& entry(const std::string& name) {
  const Entry* e = find(name);
  if (e == nullptr) {
    std::string known;
    for (const Entry& other : table()) known += std::string(known.empty() ? "" : ", ") + other.name;
    throw std::invalid_argument("unknown planner '" + name + "' (known: " + known + ")");
  }
  return *e;
}

}  // namespace

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const Entry& e : table()) names.emplace_back(e.name);
  return names;
}

std::string plannerName(const std::string& name) { return entry(name).name; }

ompl::base::PlannerPtr makePlanner(const std::string& name, const ompl::base::SpaceInformationPtr& si) {
  const Entry& e = entry(name);
  ompl::base::PlannerPtr planner = e.make(si);
  if (!e.optimizing && planner->params().hasParam("range")) {
    planner->params().setParam("range", std::to_string(defaultRange(*si)));
  }
  return planner;
}

double defaultRange(const ompl::base::SpaceInformation& si) {
  return tol::kDefaultRangeFraction * si.getMaximumExtent();
}

bool isOptimizingPlanner(const std::string& name) {
  const Entry* e = find(name);
  return e != nullptr && e->optimizing;
}

bool prepareForCostlyObjective(ompl::base::Planner& planner) {
  // InformedRRTstar derives from RRTstar.
  auto* rrtStar = dynamic_cast<og::RRTstar*>(&planner);
  if (rrtStar == nullptr) return false;
  bool changed = false;
  if (rrtStar->getKNearest()) {
    rrtStar->setKNearest(false);
    changed = true;
  }
  // A range of 0 is OMPL's "not set": setup() would make it 0.2 of the extent.
  if (rrtStar->getRange() == 0.0) {
    rrtStar->setRange(tol::kCostlyObjectiveRangeFraction * planner.getSpaceInformation()->getMaximumExtent());
    changed = true;
  }
  return changed;
}

}  // namespace deepcheck::planners
