#include "load_world.h"

#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {

std::vector<Eigen::VectorXd> readConfigurations(std::istream& in, const robots::RobotModel& robot) {
  std::vector<Eigen::VectorXd> out;
  int lineNumber = 0;
  InputLine line;
  while (nextInputLine(in, lineNumber, line)) {
    Eigen::VectorXd q(static_cast<Eigen::Index>(line.tokens.size()));
    for (Eigen::Index v = 0; v < q.size(); ++v) q[v] = parseNumber(line, line.tokens[static_cast<std::size_t>(v)]);
    if (q.size() != robot.numVariables()) {
      failAt(line, std::to_string(q.size()) + " values, robot '" + robot.name() + "' has " +
                       std::to_string(robot.numVariables()) + " variables");
    }
    out.push_back(std::move(q));
  }
  return out;
}

checker::World loadWorld(const std::string& robotPath, const std::vector<SceneArg>& scenes, const std::string& srdf,
                         const PackageRoots& paths) {
  robots::LoadOptions load;
  load.packageRoots = paths.commandLine;
  robots::RobotModel robot = robots::RobotModel::fromUrdfFile(robotPath, load);
  checker::WorldOptions options;
  if (!srdf.empty()) {
    options.disabledPairs = robots::readSrdfDisabledPairs(srdf);
    robots::checkDisabledPairs(robot, options.disabledPairs, srdf);
  }
  checker::World world(std::move(robot), options);
  for (const SceneArg& s : scenes) {
    robots::RobotModel scene = robots::RobotModel::fromUrdfFile(s.path, load);
    if (s.posed) {
      world.addScene(std::move(scene), s.X_WS);
    } else {
      world.addScene(std::move(scene));
    }
  }
  return world;
}

}  // namespace deepcheck::tools
