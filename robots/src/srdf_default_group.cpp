// A planning group for a robot whose SRDF gives none (srdf.h: defaultChainGroup).
#include "deepcheck/robots/srdf.h"

#include <stdexcept>

namespace deepcheck::robots {
namespace {

/// The moving joints between the root and link l.
int movingJointsAbove(const RobotModel& robot, int l) {
  int n = 0;
  for (int k = l; robot.link(k).parentJoint >= 0; k = robot.link(k).parentLink) {
    n += robot.joint(robot.link(k).parentJoint).moves() ? 1 : 0;
  }
  return n;
}

bool isAncestorOrSelf(const RobotModel& robot, int ancestor, int l) {
  for (int k = l; k >= 0; k = robot.link(k).parentLink) {
    if (k == ancestor) return true;
  }
  return false;
}

/// The deepest link that both a and b hang from (or are).
int commonAncestor(const RobotModel& robot, int a, int b) {
  while (!isAncestorOrSelf(robot, a, b)) a = robot.link(a).parentLink;
  return a;
}

}  // namespace

SrdfGroup defaultChainGroup(const RobotModel& robot) {
  int most = 0;
  int first = -1;  // the first leaf with `most` moving joints above it
  int tip = -1;
  for (int l = 0; l < robot.numLinks(); ++l) {
    if (!robot.link(l).childJoints.empty()) continue;  // the longest chains end at leaves
    const int n = movingJointsAbove(robot, l);
    if (n > most) {
      most = n;
      first = tip = l;
    } else if (n == most && tip >= 0) {
      tip = commonAncestor(robot, tip, l);
    }
  }
  // Chains of equal length on separate branches (two arms) meet above their moving joints: the
  // first chain is the group.
  if (tip >= 0 && movingJointsAbove(robot, tip) < most) tip = first;
  if (tip < 0) {
    throw std::invalid_argument("robot '" + robot.name() + "' has no moving joint: no planning group to make");
  }
  SrdfGroup group;
  group.name = kDefaultGroupName;
  group.chains.emplace_back(robot.link(0).name, robot.link(tip).name);
  return group;
}

}  // namespace deepcheck::robots
