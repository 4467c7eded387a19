// Problem generation as MotionBenchMaker does it (problem_generation.h): vary the scene, ground
// object-relative queries by collision-free inverse kinematics, retry until valid.

#include "deepcheck/problems/problem_generation.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/pose_goal.h"

#include <sstream>
#include <stdexcept>

namespace deepcheck::problems {

using planners::StateValidityChecker;

namespace {

/// V = translation(d) * Rz(yaw) Ry(pitch) Rx(roll), d and the angles drawn as `v` says.
Eigen::Isometry3d drawVariation(const SceneVariation& v, std::mt19937_64& rng) {
  Eigen::Vector3d d, a;
  for (int i = 0; i < 3; ++i) {
    if (v.normal) {
      d[i] = v.position[i] > 0 ? std::normal_distribution<double>(0.0, v.position[i])(rng) : 0.0;
    } else {
      d[i] = std::uniform_real_distribution<double>(-v.position[i], v.position[i])(rng);
    }
    a[i] = std::uniform_real_distribution<double>(-v.orientation[i], v.orientation[i])(rng);
  }
  Eigen::Isometry3d V = Eigen::Isometry3d::Identity();
  V.translation() = d;
  V.linear() = (Eigen::AngleAxisd(a[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(a[1], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(a[0], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return V;
}

/// The object's pose in its frame: its first shape's (see the header).
Eigen::Isometry3d objectPose(const robots::SceneObject& object) {
  return object.shapes.empty() ? object.X_FO : object.shapes.front().X_FS;
}

/// Moves every shape of `object` so that its pose X becomes X' (X_FS' = X' X^-1 X_FS).
void moveObject(robots::SceneObject& object, const Eigen::Isometry3d& X, const Eigen::Isometry3d& X_new) {
  const Eigen::Isometry3d delta = X_new * X.inverse();
  object.X_FO = delta * object.X_FO;
  for (robots::SceneShape& shape : object.shapes) shape.X_FS = delta * shape.X_FS;
}

std::string whereQuery(const QuerySet& queries, const ObjectQuery& q) {
  return "query file '" + queries.source + "', line " + std::to_string(q.line) + ", query '" + q.name() + "'";
}

}  // namespace

robots::PlanningScene varyScene(const robots::PlanningScene& nominal, const std::vector<SceneVariation>& variations,
                                std::mt19937_64& rng, const std::string& variationSource) {
  robots::PlanningScene scene = nominal;
  for (const SceneVariation& v : variations) {
    if (v.names.size() == 1 && v.names.front() == "World") {
      const Eigen::Isometry3d V = drawVariation(v, rng);
      for (robots::SceneObject& o : scene.objects) moveObject(o, objectPose(o), V * objectPose(o));
      continue;
    }
    for (const std::string& name : v.names) {
      const int i = scene.objectIndex(name);
      if (i < 0) {
        throw std::invalid_argument("variation file '" + variationSource + "', line " + std::to_string(v.line) +
                                    ": object '" + name + "' is not in the planning scene '" + nominal.source + "'");
      }
      robots::SceneObject& o = scene.objects[static_cast<std::size_t>(i)];
      moveObject(o, objectPose(o), objectPose(o) * drawVariation(v, rng));
    }
  }
  return scene;
}

Eigen::Isometry3d queryPose(const robots::PlanningScene& scene, const ObjectQuery& query,
                            const robots::RobotModel& robot, const Eigen::Ref<const Eigen::VectorXd>& q,
                            const robots::FrameAliases& aliases, const Eigen::Isometry3d& eeOffset) {
  const int i = scene.objectIndex(query.object);
  if (i < 0) {
    throw std::invalid_argument("query '" + query.name() + "' (line " + std::to_string(query.line) + "): object '" +
                                query.object + "' is not in the planning scene '" + scene.source + "'");
  }
  const robots::SceneObject& object = scene.objects[static_cast<std::size_t>(i)];
  if (object.shapes.empty()) {
    throw std::invalid_argument("query '" + query.name() + "': object '" + query.object + "' has no shape");
  }
  robots::PlanningScene one;
  one.source = scene.source;
  one.objects = {object};
  // The first shape's world pose is X_WF times the object's pose (objectPose).
  return robots::shapeWorldPoses(one, robot, q, aliases)[0][0] * query.offset * eeOffset.inverse();
}

robots::IkOptions queryIkOptions(const ObjectQuery& query, const robots::IkOptions& base,
                                 const Eigen::Isometry3d& eeOffset) {
  robots::IkOptions o = base;
  o.positionBox = query.positionTolerance;
  o.boxPose = eeOffset;
  o.orientationTolerance = query.orientationTolerance.minCoeff();
  return o;
}

namespace {

/// One attempt's state: the world's obstacles of the current scene, removed on destruction.
class SceneInWorld {
 public:
  SceneInWorld(checker::World& world, const robots::PlanningScene& scene, const checker::PlanningSceneOptions& o)
      : world_(world), ids_(world.addPlanningScene(scene, o)) {}
  ~SceneInWorld() {
    for (int id : ids_) world_.removeObstacle(id);
  }
  SceneInWorld(const SceneInWorld&) = delete;
  SceneInWorld& operator=(const SceneInWorld&) = delete;

 private:
  checker::World& world_;
  std::vector<int> ids_;
};

/// Checks that every query names an object of the scene (before any attempt).
void checkQueries(const QuerySet& queries, const robots::PlanningScene& nominal) {
  for (const auto* list : {&queries.start, &queries.goal}) {
    for (const ObjectQuery& q : *list) {
      if (nominal.objectIndex(q.object) < 0) {
        throw std::invalid_argument(whereQuery(queries, q) + ": object '" + q.object +
                                    "' is not in the planning scene '" + nominal.source + "'");
      }
    }
  }
}

/// What one problem's generation works on.
struct Generation {
  checker::World& world;
  const StateValidityChecker& checker;
  const robots::PlanningScene& nominal;
  const std::vector<SceneVariation>& variations;
  const QuerySet& queries;
  const ProblemOptions& options;
  Eigen::VectorXd q0;
  std::string variationSource;
};

/// The failed IK that came closest to its query, for the error when a problem cannot be made.
struct ClosestMiss {
  std::string query;
  robots::IkResult result;
  bool any = false;
  void offer(const std::string& name, const robots::IkResult& r) {
    if (!any || r.error.normalized < result.error.normalized) {
      query = name;
      result = r;
      any = true;
    }
  }
  std::string describe() const {
    if (!any) return "";
    std::ostringstream m;
    m << "; closest inverse kinematics: query '" << query << "', " << robots::toString(result.status)
      << ", normalized error " << result.error.normalized << " (1 = the query's tolerance; the tip "
      << result.error.position << " m and " << result.error.orientation << " rad from the query pose)";
    return m.str();
  }
};

/// Collision-free IK for `query` in the current scene; true and `q` set on success.
bool groundQuery(const Generation& g, const robots::PlanningScene& scene, const ObjectQuery& query,
                 std::mt19937_64& rng, Eigen::VectorXd& q, Eigen::Isometry3d& X_WT, ClosestMiss& miss) {
  X_WT = queryPose(scene, query, g.checker.world().robot(), g.q0, g.options.frameAliases, g.options.eeOffset);
  robots::IkOptions ik = queryIkOptions(query, g.options.ik, g.options.eeOffset);
  ik.seed = rng();
  const robots::IkResult r = solveCollisionFree(g.checker, g.options.tipLink, X_WT, ik);
  if (!r.converged()) {
    miss.offer(query.name(), r);
    return false;
  }
  q = r.q;
  return true;
}

/// One try at a problem in a freshly varied scene; true when `p` is complete.
bool tryProblem(const Generation& g, std::mt19937_64& rng, Problem& p, ClosestMiss& miss) {
  p.scene = varyScene(g.options.drawScene ? g.options.drawScene(rng) : g.nominal, g.variations, rng, g.variationSource);
  const SceneInWorld placed(g.world, p.scene, {g.options.frameAliases, g.q0});
  const QuerySet& queries = g.queries;
  const ObjectQuery& goal = queries.goal[std::uniform_int_distribution<std::size_t>(0, queries.goal.size() - 1)(rng)];
  p.goalQuery = goal.name();
  if (queries.start.empty()) {
    p.start = g.options.start;
    if (!g.checker.isValid(p.start)) return false;
  } else {
    std::vector<const ObjectQuery*> starts;
    for (const ObjectQuery& s : queries.start) {
      if (s.name() != goal.name()) starts.push_back(&s);
    }
    if (starts.empty())
      throw std::invalid_argument("query file '" + queries.source + "': no start query differs from the goal query '" +
                                  goal.name() + "'");
    const ObjectQuery& start = *starts[std::uniform_int_distribution<std::size_t>(0, starts.size() - 1)(rng)];
    p.startQuery = start.name();
    Eigen::Isometry3d X_WS;
    if (!groundQuery(g, p.scene, start, rng, p.start, X_WS, miss)) return false;
  }
  if (!groundQuery(g, p.scene, goal, rng, p.goal, p.goalPose, miss)) return false;
  const robots::RobotModel& robot = g.world.robot();
  p.goalError = robots::poseError(robot, robots::requireLink(robot, g.options.tipLink), p.goal, p.goalPose,
                                  queryIkOptions(goal, g.options.ik, g.options.eeOffset));
  return true;
}

}  // namespace

std::vector<Problem> generateProblems(checker::World& world, const StateValidityChecker& checker,
                                      const robots::PlanningScene& nominal,
                                      const std::vector<SceneVariation>& variations, const QuerySet& queries,
                                      const ProblemOptions& options, int count, const ProblemProgress& progress,
                                      const std::string& variationSource) {
  const robots::RobotModel& robot = world.robot();
  robots::requireLink(robot, options.tipLink);
  if (queries.goal.empty()) throw std::invalid_argument("query file '" + queries.source + "': no goal query");
  if (queries.start.empty() && options.start.size() != robot.numVariables()) {
    throw std::invalid_argument("the queries have no start query and the start configuration has " +
                                std::to_string(options.start.size()) + " values, not " +
                                std::to_string(robot.numVariables()));
  }
  if (count < 0 || options.maxAttempts < 1) throw std::invalid_argument("count must be >= 0 and maxAttempts >= 1");
  checkQueries(queries, nominal);
  const Generation g{world,
                     checker,
                     nominal,
                     variations,
                     queries,
                     options,
                     options.start.size() == robot.numVariables() ? options.start : robot.defaultConfiguration(),
                     variationSource};
  std::mt19937_64 rng(options.seed);
  std::vector<Problem> problems;
  for (int n = 0; n < count; ++n) {
    Problem p;
    ClosestMiss miss;
    while (!tryProblem(g, rng, p, miss)) {
      if (++p.attempts >= options.maxAttempts) {
        std::ostringstream m;
        m << "problem " << n << ": no collision-free start and goal in " << options.maxAttempts
          << " varied scenes (last goal query '" << p.goalQuery << "'"
          << (p.startQuery.empty() ? "" : ", start query '" + p.startQuery + "'") << ", tip '" << options.tipLink
          << "')" << miss.describe();
        throw std::runtime_error(m.str());
      }
    }
    ++p.attempts;
    if (progress) progress(n, p);
    problems.push_back(std::move(p));
  }
  return problems;
}

}  // namespace deepcheck::problems
