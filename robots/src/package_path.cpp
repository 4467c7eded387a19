#include "deepcheck/robots/package_path.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace fs = std::filesystem;

namespace {

/// How much of a package.xml is read to find its <name>, bytes: the name comes first in real
/// files, and a huge file under a root must not be read whole.
constexpr std::size_t kPackageXmlBytes = 64 * 1024;

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

std::vector<std::string> splitPathList(const char* value) {
  std::vector<std::string> out;
  if (value == nullptr) return out;
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, ':')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string normalized(const fs::path& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  if (ec) abs = p;
  return abs.lexically_normal().string();
}

/// The <name> declared by a package.xml, or "" when the file is absent or has none.
std::string packageXmlName(const fs::path& packageXml) {
  if (!isFile(packageXml)) return "";
  std::ifstream in(packageXml, std::ios::binary);
  std::string text(kPackageXmlBytes, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  const std::string open = "<name>";
  const std::string close = "</name>";
  const auto begin = text.find(open);
  if (begin == std::string::npos) return "";
  const auto end = text.find(close, begin + open.size());
  if (end == std::string::npos) return "";
  std::string name = text.substr(begin + open.size(), end - begin - open.size());
  const auto first = name.find_first_not_of(" \t\r\n");
  const auto last = name.find_last_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return name.substr(first, last - first + 1);
}

/// A path relative to the URDF file's folder (or absolute).
fs::path relativeToBase(const std::string& path, const std::string& baseDirectory) {
  fs::path p(path);
  if (p.is_absolute() || baseDirectory.empty()) return p;
  return fs::path(baseDirectory) / p;
}

/// True when `path` lies inside `folder` as written (no filesystem access).
bool lexicallyInside(const fs::path& path, const fs::path& folder) {
  const fs::path relative = path.lexically_normal().lexically_relative(folder.lexically_normal());
  return !relative.empty() && *relative.begin() != "..";
}

/// Records that the URI leaves `packageFolder`. The same words whether or not anything exists
/// there, so that the message tells nothing about files outside the roots.
void rejectOutside(const std::string& uri, const fs::path& packageFolder, UriResolution& out) {
  out.rejected = true;
  out.problem = "'" + uri + "' resolves outside its package root '" + normalized(packageFolder) +
                "' (a package:// path may not leave its package)";
}

/// Tries `rest` in the package folder `folder`: records the candidate, sets out.path when the file
/// is there and inside the folder, rejects it when it is outside. Returns true when done.
bool tryCandidate(const std::string& uri, const fs::path& folder, const std::string& rest, const std::string& note,
                  UriResolution& out) {
  const fs::path candidate = folder / rest;
  if (!lexicallyInside(candidate, folder)) {
    rejectOutside(uri, folder, out);
    return true;
  }
  out.searched.push_back(normalized(candidate) + note);
  if (!isFile(candidate)) return false;
  // A symbolic link inside the package is followed wherever it points: the package's owner put it
  // there (colcon --symlink-install links every installed file back to the sources).
  out.path = normalized(candidate);
  return true;
}

/// The direct subfolders of `root` (other than one named `package`) whose package.xml declares
/// `package`, sorted (directory order is unspecified).
std::vector<fs::path> renamedPackageFolders(const fs::path& root, const std::string& package) {
  std::vector<fs::path> matches;
  std::error_code ec;
  fs::directory_iterator it(root, ec);
  if (ec) return matches;
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) break;
    std::error_code dirEc;
    if (!it->is_directory(dirEc) || it->path().filename() == package) continue;
    if (packageXmlName(it->path() / "package.xml") == package) matches.push_back(it->path());
  }
  std::sort(matches.begin(), matches.end());
  return matches;
}

void resolvePackage(const std::string& uri, const std::vector<std::string>& roots, UriResolution& out) {
  const std::string body = uri.substr(std::string("package://").size());
  const auto slash = body.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= body.size()) {
    out.problem = "malformed package URI (expected package://PACKAGE/path)";
    return;
  }
  const std::string package = body.substr(0, slash);
  const std::string rest = body.substr(slash + 1);
  if (package == "." || package == ".." || fs::path(rest).is_absolute()) {
    out.problem = "malformed package URI (the package must be a name and the path relative)";
    return;
  }
  if (roots.empty()) {
    out.problem =
        "no package roots to search (set LoadOptions::packageRoots, or ROS_PACKAGE_PATH with "
        "LoadOptions::useRosPackagePath)";
    return;
  }
  for (const std::string& rootString : roots) {
    const fs::path root(rootString);
    // The plain ROS rule: <root>/<package>/<rest>.
    if (tryCandidate(uri, root / package, rest, "", out)) return;
    // The root is itself the package.
    if (packageXmlName(root / "package.xml") == package && tryCandidate(uri, root, rest, "", out)) return;
    // A direct subfolder whose package.xml declares the package under another folder name.
    for (const fs::path& dir : renamedPackageFolders(root, package)) {
      const std::string note = " (package.xml of " + dir.filename().string() + " names " + package + ")";
      if (tryCandidate(uri, dir, rest, note, out)) return;
    }
  }
  out.problem = "package '" + package + "' has no file '" + rest + "' in any package root";
}

}  // namespace

std::vector<std::string> packageRoots(const std::vector<std::string>& callerRoots, bool useEnvironment) {
  std::vector<std::string> roots;
  auto add = [&roots](const std::string& r) {
    if (!r.empty() && std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
  };
  for (const std::string& r : callerRoots) add(r);
  if (useEnvironment) {
    for (const std::string& r : splitPathList(std::getenv("ROS_PACKAGE_PATH"))) add(r);
    for (const std::string& prefix : splitPathList(std::getenv("AMENT_PREFIX_PATH"))) {
      add((fs::path(prefix) / "share").string());
    }
  }
  return roots;
}

UriResolution resolveUri(const std::string& uri, const std::vector<std::string>& roots,
                         const std::string& baseDirectory) {
  UriResolution out;
  if (uri.empty()) {
    out.problem = "empty mesh filename";
    return out;
  }
  if (startsWith(uri, "package://")) {
    resolvePackage(uri, roots, out);
    return out;
  }
  std::string path = uri;
  if (startsWith(uri, "file://")) {
    path = uri.substr(std::string("file://").size());
    if (path.empty()) {
      out.problem = "malformed file URI (no path after file://)";
      return out;
    }
  } else if (uri.find("://") != std::string::npos) {
    out.problem = "unsupported URI scheme (only package://, file:// and plain paths are)";
    return out;
  }
  const fs::path candidate = relativeToBase(path, baseDirectory);
  out.searched.push_back(normalized(candidate));
  if (isFile(candidate)) {
    out.path = normalized(candidate);
  } else {
    out.problem = "no such file";
  }
  return out;
}

std::string resolveUriOrThrow(const std::string& uri, const std::vector<std::string>& roots,
                              const std::string& baseDirectory, const std::string& context) {
  UriResolution r = resolveUri(uri, roots, baseDirectory);
  if (r.found()) return r.path;
  if (r.rejected) throw std::invalid_argument(context + ": mesh " + r.problem);
  std::string message = context + ": cannot find mesh '" + uri + "': " + r.problem;
  if (!r.searched.empty()) {
    message += "; searched:";
    for (const std::string& s : r.searched) message += "\n  " + s;
  }
  throw std::invalid_argument(message);
}

}  // namespace deepcheck::robots
