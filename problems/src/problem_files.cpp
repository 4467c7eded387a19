// MotionBenchMaker's variation, query and robot files (problem_generation.h): checked reading,
// every error naming the file, the line and the value.

#include "deepcheck/problems/problem_generation.h"
#include "deepcheck/robots/joint_angles.h"
#include "deepcheck/robots/planning_group.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace deepcheck::problems {

namespace {

/// "a list", "a scalar", ...: what a node is, for messages.
std::string shapeOf(const YAML::Node& node) {
  if (node.IsSequence()) return "a list";
  if (node.IsScalar()) return "a scalar ('" + node.Scalar() + "')";
  if (node.IsNull()) return "an empty value";
  return "a map";
}

/// Reads values of one file; fail() throws "<kind> '<file>', line <n>: <what>".
struct Reader {
  std::string kind;
  std::string source;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& what) const {
    std::string message = kind + " '" + source + "'";
    if (node.IsDefined() && !node.Mark().is_null()) message += ", line " + std::to_string(node.Mark().line + 1);
    throw std::invalid_argument(message + ": " + what);
  }
  YAML::Node required(const YAML::Node& parent, const char* key) const {
    // yaml-cpp throws YAML::BadSubscript when a scalar is indexed by a key: the file's error instead.
    if (!parent.IsMap()) fail(parent, std::string("'") + key + "' must be a key of a map, not of " + shapeOf(parent));
    const YAML::Node node = parent[key];
    if (!node.IsDefined()) fail(parent, std::string("missing '") + key + "'");
    return node;
  }
  std::string text(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a string");
    return node.Scalar();
  }
  std::vector<std::string> texts(const YAML::Node& node, const std::string& what) const {
    if (!node.IsSequence() || node.size() == 0) fail(node, what + " must be a non-empty list");
    std::vector<std::string> out;
    for (const YAML::Node& n : node) out.push_back(text(n, what + " entry"));
    return out;
  }
  double number(const YAML::Node& node, const std::string& what) const {
    double v = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, v)) {
      fail(node, what + " must be a number, not '" + (node.IsScalar() ? node.Scalar() : "a list or map") + "'");
    }
    if (!std::isfinite(v)) fail(node, what + " must be finite, not '" + node.Scalar() + "'");
    return v;
  }
  std::vector<double> numbers(const YAML::Node& node, const std::string& what, std::size_t n) const {
    if (!node.IsSequence() || (n != 0 && node.size() != n)) {
      fail(node, what + " must be a list of " + (n ? std::to_string(n) + " numbers" : "numbers"));
    }
    std::vector<double> out;
    for (const YAML::Node& v : node) out.push_back(number(v, what + " entry"));
    return out;
  }
  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& what, bool nonNegative) const {
    const std::vector<double> v = numbers(node, what, 3);
    if (nonNegative && (v[0] < 0 || v[1] < 0 || v[2] < 0)) fail(node, what + " entries must not be negative");
    return Eigen::Vector3d(v[0], v[1], v[2]);
  }
  /// Runs `read` (which reads the nodes of this file): a yaml-cpp exception that escapes it (a
  /// conversion or subscript the checks above do not foresee) becomes this file's error.
  template <class Read>
  auto guarded(Read read) const -> decltype(read()) {
    try {
      return read();
    } catch (const YAML::Exception& e) {
      std::string message = kind + " '" + source + "'";
      if (!e.mark.is_null()) message += ", line " + std::to_string(e.mark.line + 1);
      throw std::invalid_argument(message + ": " + e.msg);
    }
  }
  YAML::Node parse(const std::string& yaml) const {
    try {
      return YAML::Load(yaml);
    } catch (const YAML::Exception& e) {
      std::string message = kind + " '" + source + "'";
      if (!e.mark.is_null()) message += ", line " + std::to_string(e.mark.line + 1);
      throw std::invalid_argument(message + ": malformed YAML: " + e.msg);
    }
  }
};

std::string readFile(const std::string& path, const std::string& kind) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(kind + " '" + path + "': cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

SceneVariation readVariation(const Reader& r, const YAML::Node& node) {
  if (!node.IsMap()) r.fail(node, "a variation must be a map with names, position, orientation and type");
  SceneVariation v;
  v.line = node.Mark().line + 1;
  v.names = r.texts(r.required(node, "names"), "names");
  v.position = r.vector3(r.required(node, "position"), "position", true);
  v.orientation = r.vector3(r.required(node, "orientation"), "orientation", true);
  const YAML::Node typeNode = r.required(node, "type");
  const std::string type = r.text(typeNode, "type");
  if (type == "gaussian" || type == "normal") {
    v.normal = true;
  } else if (type != "uniform") {
    r.fail(typeNode, "unknown variation type '" + type + "' (uniform, gaussian or normal)");
  }
  return v;
}

ObjectQuery readQuery(const Reader& r, const YAML::Node& offset, const std::string& object, const std::string& tag) {
  ObjectQuery q;
  q.object = object;
  q.tag = tag;
  q.line = offset.Mark().line + 1;
  const Eigen::Vector3d p = r.vector3(r.required(offset, "position"), "offset position", false);
  const YAML::Node o = r.required(offset, "orientation");
  const std::vector<double> x = r.numbers(o, "offset orientation (x y z w)", 4);
  // Rounded by hand like a scene's quaternions ([0, 0.707, 0, 0.707]): the scene's tolerance.
  const Eigen::Quaterniond quaternion(x[3], x[0], x[1], x[2]);
  if (std::abs(quaternion.norm() - 1.0) > robots::tol::kSceneQuaternionNorm) {
    std::ostringstream m;
    m << "offset orientation (x y z w) is not a unit quaternion: its norm is " << quaternion.norm();
    r.fail(o, m.str());
  }
  q.offset = Eigen::Isometry3d::Identity();
  q.offset.linear() = quaternion.normalized().toRotationMatrix();
  q.offset.translation() = p;
  q.positionTolerance = r.vector3(r.required(offset, "position_tol"), "position_tol", true);
  q.orientationTolerance = r.vector3(r.required(offset, "orientation_tol"), "orientation_tol", true);
  if (q.positionTolerance.minCoeff() <= 0 || q.orientationTolerance.minCoeff() <= 0) {
    r.fail(offset, "position_tol and orientation_tol entries must be positive");
  }
  return q;
}

std::vector<ObjectQuery> readQueries(const Reader& r, const YAML::Node& list, const char* key) {
  if (!list.IsSequence()) r.fail(list, std::string("'") + key + "' must be a list");
  std::vector<ObjectQuery> out;
  for (const YAML::Node& entry : list) {
    if (!entry.IsMap()) r.fail(entry, "a query must be a map with objects, tag and offset");
    const std::string tag = r.text(r.required(entry, "tag"), "tag");
    const YAML::Node attached = entry["attached"];
    if (attached.IsDefined() && r.text(attached, "attached") != "False" && attached.Scalar() != "false") {
      r.fail(attached, "attached queries are not supported (attached: '" + attached.Scalar() + "')");
    }
    const YAML::Node offset = r.required(entry, "offset");
    for (const std::string& object : r.texts(r.required(entry, "objects"), "objects")) {
      out.push_back(readQuery(r, offset, object, tag));
    }
  }
  return out;
}

}  // namespace

std::vector<SceneVariation> parseSceneVariations(const std::string& yaml, const std::string& sourceName) {
  const Reader r{"variation file", sourceName};
  return r.guarded([&] {
    const YAML::Node root = r.parse(yaml);
    if (!root.IsSequence()) r.fail(root, "the file must be a list of variations");
    std::vector<SceneVariation> out;
    for (const YAML::Node& node : root) out.push_back(readVariation(r, node));
    return out;
  });
}

std::vector<SceneVariation> loadSceneVariations(const std::string& path) {
  return parseSceneVariations(readFile(path, "variation file"), path);
}

QuerySet parseQueries(const std::string& yaml, const std::string& sourceName) {
  const Reader r{"query file", sourceName};
  return r.guarded([&] {
    const YAML::Node root = r.parse(yaml);
    if (!root.IsMap()) r.fail(root, "the file must be a map with goal_queries (and start_queries)");
    QuerySet set;
    set.source = sourceName;
    for (const auto& kv : root) {
      const std::string key = kv.first.Scalar();
      if (key == "goal_queries") {
        set.goal = readQueries(r, kv.second, "goal_queries");
      } else if (key == "start_queries") {
        set.start = readQueries(r, kv.second, "start_queries");
      } else {
        r.fail(kv.first, "unknown key '" + key + "' (goal_queries, start_queries)");
      }
    }
    if (set.goal.empty()) r.fail(root, "no goal query: 'goal_queries' is missing or empty");
    return set;
  });
}

QuerySet loadQueries(const std::string& path) { return parseQueries(readFile(path, "query file"), path); }

RobotConfig parseRobotConfig(const std::string& yaml, const std::string& sourceName) {
  const Reader r{"robot configuration", sourceName};
  return r.guarded([&] {
    const YAML::Node root = r.parse(yaml);
    if (!root.IsMap()) r.fail(root, "the file must be a map");
    RobotConfig c;
    c.source = sourceName;
    if (root["urdf"].IsDefined()) c.urdf = r.text(root["urdf"], "urdf");
    if (root["srdf"].IsDefined()) c.srdf = r.text(root["srdf"], "srdf");
    const YAML::Node state = r.required(root, "robot_state");
    c.line = state.Mark().line + 1;
    const YAML::Node joints = r.required(state, "joint_state");
    const YAML::Node names = r.required(joints, "name");
    c.jointNames = r.texts(names, "joint_state name");
    c.jointPositions = r.numbers(r.required(joints, "position"), "joint_state position", c.jointNames.size());
    return c;
  });
}

RobotConfig loadRobotConfig(const std::string& path) {
  return parseRobotConfig(readFile(path, "robot configuration"), path);
}

Eigen::VectorXd configurationOf(const robots::RobotModel& robot, const RobotConfig& config,
                                std::vector<std::string>* notes) {
  Eigen::VectorXd q = robot.defaultConfiguration();
  const std::string where = "robot configuration '" + config.source + "', line " + std::to_string(config.line);
  for (std::size_t i = 0; i < config.jointNames.size(); ++i) {
    const std::string& name = config.jointNames[i];
    const int joint = robot.jointIndex(name);
    if (joint < 0) throw std::invalid_argument(where + ": the robot has no joint '" + name + "'");
    const int v = robot.variableIndex(name);
    const double x = config.jointPositions[i];
    const robots::Joint& j = robot.joint(joint);
    if (j.locked && x != j.lockedValue && notes) {
      std::ostringstream m;
      m << where << ": joint '" << name << "' = " << x << " is held at " << j.lockedValue << " (locked)";
      notes->push_back(m.str());
    }
    if (v < 0) continue;  // a mimic joint follows its variable; a locked one keeps its value
    if (robots::isWrappingVariable(robot, v)) {
      q[v] = robots::normalizeAngle(x);  // the same angle, not outside any limit
      continue;
    }
    q[v] = std::clamp(x, robot.lowerLimits()[v], robot.upperLimits()[v]);
    if (q[v] != x && notes) {
      std::ostringstream m;
      m << where << ": joint '" << name << "' = " << x << " is outside its limits [" << robot.lowerLimits()[v] << ", "
        << robot.upperLimits()[v] << "] of '" << robot.source() << "'; clamped to " << q[v];
      notes->push_back(m.str());
    }
  }
  return q;
}

std::map<std::string, double> lockedOutsideGroup(const robots::RobotModel& robot, const RobotConfig& config,
                                                 const std::string& srdf, const std::string& group) {
  const std::vector<int> moved = robots::groupVariables(robot, robots::readSrdfGroups(srdf), group, srdf);
  const Eigen::VectorXd q = configurationOf(robot, config);
  std::map<std::string, double> locked;
  for (int v = 0; v < robot.numVariables(); ++v) {
    if (std::find(moved.begin(), moved.end(), v) == moved.end()) {
      locked.emplace(robot.variableNames()[static_cast<std::size_t>(v)], q[v]);
    }
  }
  return locked;
}

}  // namespace deepcheck::problems
