// Pairs that no joint can change (world.h, "Fixed pairs"): listed by World::fixedPairs and
// reported once each on WorldOptions::progress when the world's scenes, obstacles or allowed
// collisions change.

#include "deepcheck/checker/world.h"

#include "world_internal.h"


#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>

namespace deepcheck::checker {

bool movedByNoJoint(const robots::RobotModel& model, int link) {
  for (int l = link; model.link(l).parentJoint >= 0; l = model.link(l).parentLink) {
    if (model.joint(model.link(l).parentJoint).moves()) return false;
  }
  return true;
}

namespace detail {

std::string allowHint(const Contact& c) {
  return "allow it with --allow-collision " + c.nameA + ":" + c.nameB + " (World::allowCollision)";
}

namespace {

/// A distance in metres with 3 significant digits (-0.003, 0.0125): the reports' precision.
std::string metres(double d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", d);
  return text;
}

}  // namespace

std::string fixedPairMessage(const Contact& c, const robots::RobotModel& robot) {
  const std::string link = robot.link(c.linkA).name;
  const std::string what = c.distance <= 0.0 ? "every configuration collides"
                                             : "no configuration has a clearance above it";
  return "deepcheck: warning: " + c.nameA + " and " + c.nameB + " are " + metres(c.distance) +
         " m apart in every configuration (no joint moves " + link + "): " + what + "; " + allowHint(c);
}

void reportFixedPairs(const World& world, WorldState& st) {
  if (st.options.progress == nullptr || !st.fixedPairReports.load()) return;
  const std::vector<Contact> pairs = world.fixedPairs();
  std::lock_guard<std::mutex> lock(st.mutex);
  for (const Contact& c : pairs) {
    if (!st.reportedFixedPairs.insert(c.nameA + "\n" + c.nameB).second) continue;
    *st.options.progress << fixedPairMessage(c, world.robot()) << "\n";
  }
  st.options.progress->flush();
}

}  // namespace detail

bool World::setFixedPairReports(bool on) {
  const bool before = state_->fixedPairReports.exchange(on);
  if (on) detail::reportFixedPairs(*this, *state_);
  return before;
}

std::vector<Contact> World::fixedPairs(double maxDistance) const {
  const robots::RobotModel& model = state_->robot->model;
  DistanceOptions options;
  options.selfPairs = false;
  options.maxDistance = std::nextafter(maxDistance, std::numeric_limits<double>::infinity());
  options.contactMargin = maxDistance;
  Context context = makeContext();
  const DistanceResult r = signedDistance(model.defaultConfiguration(), context, options);
  std::vector<Contact> out;
  for (const Contact& c : r.contacts) {
    if (movedByNoJoint(model, c.linkA)) out.push_back(c);
  }
  return out;
}

}  // namespace deepcheck::checker
