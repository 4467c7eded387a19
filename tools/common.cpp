#include "common.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace deepcheck::tools {

bool takeFlag(std::vector<std::string>& args, const std::string& name) {
  const auto end = std::remove(args.begin(), args.end(), name);
  const bool found = end != args.end();
  args.erase(end, args.end());
  return found;
}

std::vector<std::string> takeOption(std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> values;
  std::vector<std::string> rest;
  const std::string prefix = name + "=";
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string value;
    if (args[i] == name) {
      if (i + 1 == args.size()) throw UsageError("option " + name + " needs a value");
      value = args[++i];
    } else if (args[i].compare(0, prefix.size(), prefix) == 0) {
      value = args[i].substr(prefix.size());
    } else {
      rest.push_back(args[i]);
      continue;
    }
    if (value.empty()) throw UsageError("option " + name + " needs a non-empty value");
    values.push_back(value);
  }
  args = std::move(rest);
  return values;
}

std::vector<std::string> splitPathList(const std::string& list) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t colon = std::min(list.find(':', start), list.size());
    if (colon > start) parts.push_back(list.substr(start, colon - start));
    start = colon + 1;
  }
  return parts;
}

std::vector<std::string> PackagePaths::roots() const {
  std::vector<std::string> all;
  for (const auto* list : {&commandLine, &environment}) {
    for (const auto& p : *list) {
      if (std::find(all.begin(), all.end(), p) == all.end()) all.push_back(p);
    }
  }
  return all;
}

PackagePaths takePackagePaths(std::vector<std::string>& args, bool useEnvironment) {
  PackagePaths paths;
  paths.commandLine = takeOption(args, "--package-path");
  if (useEnvironment) {
    if (const char* env = std::getenv("ROS_PACKAGE_PATH")) paths.environment = splitPathList(env);
  }
  return paths;
}

void rejectUnknownOptions(const std::vector<std::string>& args) {
  for (const auto& a : args) {
    if (a.size() > 1 && a[0] == '-') throw UsageError("unknown option '" + a + "'");
  }
}

double parseValue(const std::string& text, const std::string& what) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || !std::isfinite(value)) {
    throw UsageError(what + " needs a finite number, got '" + text + "'");
  }
  return value;
}

void takeWorldOptions(std::vector<std::string>& args, std::string& robot, std::vector<SceneArg>& scenes,
                      std::string& srdf) {
  std::vector<std::string> rest;
  auto valueOf = [&](std::size_t& i, const std::string& name) {
    const std::string prefix = name + "=";
    std::string value;
    if (args[i] == name) {
      if (i + 1 == args.size()) throw UsageError("option " + name + " needs a value");
      value = args[++i];
    } else {
      value = args[i].substr(prefix.size());
    }
    if (value.empty()) throw UsageError("option " + name + " needs a non-empty value");
    return value;
  };
  auto is = [&](const std::string& arg, const std::string& name) {
    return arg == name || arg.compare(0, name.size() + 1, name + "=") == 0;
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (is(args[i], "--robot")) {
      if (!robot.empty()) throw UsageError("option --robot given more than once");
      robot = valueOf(i, "--robot");
    } else if (is(args[i], "--srdf")) {
      if (!srdf.empty()) throw UsageError("option --srdf given more than once");
      srdf = valueOf(i, "--srdf");
    } else if (is(args[i], "--scene")) {
      scenes.push_back(SceneArg{valueOf(i, "--scene")});
    } else if (args[i] == "--scene-pose") {
      if (scenes.empty()) throw UsageError("--scene-pose must follow a --scene");
      if (scenes.back().posed) throw UsageError("--scene-pose given twice for scene '" + scenes.back().path + "'");
      if (i + 6 >= args.size()) throw UsageError("--scene-pose needs 6 numbers: x y z roll pitch yaw");
      double v[6];
      static const char* const names[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
      for (int k = 0; k < 6; ++k) v[k] = parseValue(args[i + 1 + k], std::string("--scene-pose ") + names[k]);
      i += 6;
      SceneArg& s = scenes.back();
      s.posed = true;
      s.X_WS.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
      s.X_WS.linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                         Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                            .toRotationMatrix();
    } else {
      rest.push_back(args[i]);
    }
  }
  args = std::move(rest);
  if (robot.empty()) throw UsageError("option --robot is required");
}

}  // namespace deepcheck::tools
