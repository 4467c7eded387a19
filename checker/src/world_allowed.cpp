// Allowed collisions (an allowed-collision matrix by name): which body pairs the queries skip.
//
// A name stands for every body it is an alias of (bodyAliases in world_internal.h): a robot link,
// an attached object, a scene link, an obstacle, or all the obstacles of a planning-scene object.
// An allowed pair is skipped by every query (isFree, signedDistance, contacts, and so the
// clearance and push-out built on them). Robot link pairs join the disabled self pairs (an SRDF's
// <disable_collisions> are entered here too); robot-world pairs are tested against a mask per
// piece set, rebuilt at every change of the world (publish).

#include "deepcheck/checker/world.h"

#include "near_matches.h"
#include "world_internal.h"

#include <algorithm>
#include <stdexcept>

namespace deepcheck::checker {

using detail::Snapshot;
using detail::WorldState;

namespace detail {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

std::vector<std::string> bodyAliases(const std::string& bodyName, const robots::RobotModel& robot) {
  std::vector<std::string> out{bodyName};
  // A name without its prefix, unless a robot link has it: an SRDF's pair (base_link, shoulder)
  // must not allow a scene's link "base_link" against the shoulder.
  const auto bare = [&](const std::string& name) {
    if (robot.linkIndex(name) < 0) out.push_back(name);
  };
  if (startsWith(bodyName, "scene/")) bare(bodyName.substr(6));
  for (const std::string prefix : {"obstacle/", "attached/"}) {
    if (!startsWith(bodyName, prefix)) continue;
    const std::string name = bodyName.substr(prefix.size());
    bare(name);
    // "<id>/<k>": the k-th shape of a planning-scene object, also named by the object's id.
    const std::size_t slash = name.rfind('/');
    if (slash != std::string::npos && slash > 0) {
      bare(name.substr(0, slash));
      out.push_back(prefix + name.substr(0, slash));
    }
  }
  return out;
}

std::vector<std::string> groupAliases(const Snapshot& s, int g) {
  const LinkGeometry& lg = s.robot->links[static_cast<std::size_t>(g)];
  if (lg.attached < 0) return {s.robot->model.link(lg.link).name};
  return bodyAliases("attached/" + s.attached[static_cast<std::size_t>(lg.attached)]->source.name, s.robot->model);
}

bool allowedByName(const AllowedNames& allowed, const std::vector<std::string>& a, const std::vector<std::string>& b) {
  if (allowed.empty()) return false;
  for (const std::vector<std::string>* names : {&a, &b}) {
    for (const std::string& n : *names) {
      if (allowed.always.count(n) > 0) return true;
    }
  }
  for (const std::string& x : a) {
    for (const std::string& y : b) {
      if (allowed.pairs.count(std::minmax(x, y)) > 0) return true;
    }
  }
  return false;
}

namespace {

/// Every name the allowed entries mention.
std::set<std::string> mentioned(const AllowedNames& allowed) {
  std::set<std::string> out = allowed.always;
  for (const auto& [a, b] : allowed.pairs) {
    out.insert(a);
    out.insert(b);
  }
  return out;
}

/// The mask of `set`: a body none of whose aliases is mentioned is allowed only with the robot
/// geometries allowed to touch anything (the common case, checked without a name lookup).
AllowedMask maskOf(const Snapshot& s, const PieceSet& set, const std::set<std::string>& names,
                   const std::vector<std::vector<std::string>>& groups) {
  std::vector<bool> groupAlways(groups.size(), false);
  for (std::size_t g = 0; g < groups.size(); ++g) groupAlways[g] = allowedByName(s.allowed, groups[g], {});
  AllowedMask mask;
  mask.bodies = set.bodies.size();
  for (std::size_t b = 0; b < set.bodies.size(); ++b) {
    const std::vector<std::string> body = bodyAliases(set.bodies[b].name, s.robot->model);
    const bool named = std::any_of(body.begin(), body.end(), [&](const std::string& n) { return names.count(n) > 0; });
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (!(named ? allowedByName(s.allowed, groups[g], body) : groupAlways[g])) continue;
      if (mask.bits.empty()) mask.bits.assign(groups.size() * set.bodies.size(), 0);
      mask.bits[g * mask.bodies + b] = 1;
    }
  }
  return mask;
}

}  // namespace

void buildAllowedMasks(Snapshot& s) {
  s.sceneAllowed = AllowedMask{};
  s.obstacleAllowed = AllowedMask{};
  if (s.allowed.empty()) return;
  const std::set<std::string> names = mentioned(s.allowed);
  std::vector<std::vector<std::string>> groups;
  for (int g = 0; g < static_cast<int>(s.robot->links.size()); ++g) groups.push_back(groupAliases(s, g));
  s.sceneAllowed = maskOf(s, *s.scenePieces, names, groups);
  s.obstacleAllowed = maskOf(s, *s.obstaclePieces, names, groups);
}

std::set<std::pair<int, int>> allowedLinkPairs(const Snapshot& s) {
  std::set<std::pair<int, int>> out;
  if (s.allowed.empty()) return out;
  const RobotData& robot = *s.robot;
  std::vector<int> links;
  for (const LinkGeometry& g : robot.links) {
    if (g.attached < 0) links.push_back(g.link);
  }
  const robots::RobotModel& m = robot.model;
  for (std::size_t i = 0; i < links.size(); ++i) {
    for (std::size_t j = i + 1; j < links.size(); ++j) {
      if (allowedByName(s.allowed, {m.link(links[i]).name}, {m.link(links[j]).name})) out.insert({links[i], links[j]});
    }
  }
  return out;
}

}  // namespace detail

namespace {

/// The canonical names of every body of `s` ("base_link", "attached/box", "scene/table",
/// "obstacle/shelf/0"); robot links without geometry included.
std::vector<std::string> bodies(const Snapshot& s) {
  std::vector<std::string> out;
  for (const robots::Link& l : s.robot->model.links()) out.push_back(l.name);
  for (const auto& a : s.attached) out.push_back("attached/" + a->source.name);
  for (const auto& scene : s.scenes) {
    for (const robots::Link& l : scene->model.links()) out.push_back("scene/" + l.name);
  }
  for (const auto& o : s.obstacles) out.push_back("obstacle/" + o->source.name);
  return out;
}

/// Every name a body of `s` answers to, sorted.
std::vector<std::string> knownNames(const Snapshot& s) {
  std::vector<std::string> out;
  for (const std::string& body : bodies(s)) {
    for (const std::string& n : detail::bodyAliases(body, s.robot->model)) out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Throws std::invalid_argument, naming `what` and the near matches, unless `name` names a body.
void checkName(const Snapshot& s, const std::string& name, const std::string& what) {
  const std::vector<std::string> known = knownNames(s);
  if (std::binary_search(known.begin(), known.end(), name)) return;
  throw std::invalid_argument(what + ": no robot link, attached object, scene link or obstacle is named '" + name +
                              "'" + detail::nearMatchesText(name, known));
}

/// The aliases of every body `name` names.
std::vector<std::vector<std::string>> aliasesOfBodiesNamed(const Snapshot& s, const std::string& name) {
  std::vector<std::vector<std::string>> out;
  for (const std::string& body : bodies(s)) {
    std::vector<std::string> aliases = detail::bodyAliases(body, s.robot->model);
    if (std::find(aliases.begin(), aliases.end(), name) != aliases.end()) out.push_back(std::move(aliases));
  }
  return out;
}

}  // namespace

void World::allowCollision(const std::string& a, const std::string& b) {
  if (b == "*") return allowCollisionsWith(a);
  if (a == "*") return allowCollisionsWith(b);
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  checkName(*st.current, a, "allowCollision");
  checkName(*st.current, b, "allowCollision");
  auto snap = std::make_shared<Snapshot>(*st.current);
  snap->allowed.pairs.insert(std::minmax(a, b));
  detail::rebuildSelfPairs(*snap, st.options);
  detail::publish(st, snap);
}

void World::allowCollisionsWith(const std::string& name) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  checkName(*st.current, name, "allowCollisionsWith");
  auto snap = std::make_shared<Snapshot>(*st.current);
  snap->allowed.always.insert(name);
  detail::rebuildSelfPairs(*snap, st.options);
  detail::publish(st, snap);
}

std::vector<std::pair<std::string, std::string>> World::allowedCollisions() const {
  const auto snap = state_->snapshot();
  std::vector<std::pair<std::string, std::string>> out(snap->allowed.pairs.begin(), snap->allowed.pairs.end());
  for (const std::string& n : snap->allowed.always) out.emplace_back(n, "*");
  return out;
}

bool World::collisionAllowed(const std::string& a, const std::string& b) const {
  const auto snap = state_->snapshot();
  if (a != "*") checkName(*snap, a, "collisionAllowed");
  if (b != "*") checkName(*snap, b, "collisionAllowed");
  if (a == "*" || b == "*") return snap->allowed.always.count(a == "*" ? b : a) > 0;
  // Every body a names against every body b names.
  for (const auto& x : aliasesOfBodiesNamed(*snap, a)) {
    for (const auto& y : aliasesOfBodiesNamed(*snap, b)) {
      if (!detail::allowedByName(snap->allowed, x, y)) return false;
    }
  }
  return true;
}

}  // namespace deepcheck::checker
