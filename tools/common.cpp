#include "common.h"

#include <algorithm>
#include <cstdlib>

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

}  // namespace deepcheck::tools
