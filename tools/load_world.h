#pragma once
// The collision world of the command line (--robot, --scene [--scene-pose], --srdf,
// --package-path), shared by the subcommands that query it.

#include "common.h"

#include "deepcheck/checker/world.h"

#include <Eigen/Core>

#include <istream>
#include <string>
#include <vector>

namespace deepcheck::tools {

/// Configurations, one per line (joint values in the robot's variable order; '#' comments and
/// blank lines skipped); throws InputError naming the line (a bad number, a wrong count).
std::vector<Eigen::VectorXd> readConfigurations(std::istream& in, const robots::RobotModel& robot);

/// Loads the robot, disables the SRDF's pairs (an unknown link in it is an error naming the file)
/// and adds the scenes. Throws std::invalid_argument naming the bad file.
checker::World loadWorld(const std::string& robotPath, const std::vector<SceneArg>& scenes, const std::string& srdf,
                         const PackageRoots& paths);

}  // namespace deepcheck::tools
