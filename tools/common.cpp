#include "common.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
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

std::string takeSingleOption(std::vector<std::string>& args, const std::string& name, const std::string& fallback) {
  const std::vector<std::string> values = takeOption(args, name);
  if (values.size() > 1) throw UsageError("option " + name + " given more than once");
  return values.empty() ? fallback : values.front();
}

PackageRoots takePackageRoots(std::vector<std::string>& args) {
  return PackageRoots{takeOption(args, "--package-path")};
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

std::uint64_t parseCount(const std::string& text, const std::string& option, std::uint64_t min, std::uint64_t max) {
  std::uint64_t value = 0;
  bool ok = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  if (ok) {
    try {
      value = std::stoull(text);
    } catch (const std::exception&) {  // out of range
      ok = false;
    }
  }
  if (!ok || value < min || value > max) {
    throw UsageError("option " + option + " needs a whole number from " + std::to_string(min) + " to " +
                     std::to_string(max) + ", got '" + text + "'");
  }
  return value;
}

std::vector<double> takeVector(std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> rest;
  std::vector<double> values;
  bool seen = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] != name) {
      rest.push_back(args[i]);
      continue;
    }
    if (seen) throw UsageError("option " + name + " given more than once");
    seen = true;
    while (i + 1 < args.size() && args[i + 1].compare(0, 2, "--") != 0) {
      values.push_back(parseValue(args[++i], name));
    }
    if (values.empty()) throw UsageError("option " + name + " needs the joint values");
  }
  args = std::move(rest);
  return values;
}

void takeWorldOptions(std::vector<std::string>& args, std::string& robot, std::vector<SceneArg>& scenes,
                      std::vector<std::string>& srdfs) {
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
      srdfs.push_back(valueOf(i, "--srdf"));
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
      s.X_WS.linear() =
          (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
              .toRotationMatrix();
    } else {
      rest.push_back(args[i]);
    }
  }
  args = std::move(rest);
  if (robot.empty()) throw UsageError("option --robot is required");
}

std::string formatDuration(double seconds) {
  char text[48];
  if (seconds < 1e-3) {
    std::snprintf(text, sizeof text, "%.0f us", seconds * 1e6);
  } else if (seconds < 1.0) {
    std::snprintf(text, sizeof text, "%.1f ms", seconds * 1e3);
  } else {
    std::snprintf(text, sizeof text, "%.2f s", seconds);
  }
  return text;
}

namespace {

std::vector<std::string> tokenize(const std::string& s) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    const std::size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) tokens.push_back(s.substr(start, i - start));
  }
  return tokens;
}

}  // namespace

bool nextInputLine(std::istream& in, int& lineNumber, InputLine& line) {
  std::string text;
  while (std::getline(in, text)) {
    ++lineNumber;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    std::vector<std::string> tokens = tokenize(text);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    line.number = lineNumber;
    line.text = std::move(text);
    line.tokens = std::move(tokens);
    return true;
  }
  return false;
}

void failAt(const InputLine& line, const std::string& problem) {
  throw InputError("line " + std::to_string(line.number) + ": " + problem + ": '" + line.text + "'");
}

double parseNumber(const InputLine& line, const std::string& token) {
  const char* begin = token.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0') failAt(line, "'" + token + "' is not a number");
  if (!std::isfinite(value)) failAt(line, "'" + token + "' is not a finite number");
  return value;
}

}  // namespace deepcheck::tools
