#pragma once
// Resolving the mesh addresses found in URDF files to files on disk.
//
// Three forms are accepted:
//   package://PKG/rest   the ROS way: the first existing file among, for each package root R in
//                        order (the caller's roots first, then the entries of ROS_PACKAGE_PATH,
//                        then <prefix>/share for each entry of AMENT_PREFIX_PATH):
//                          R/PKG/rest                       (the plain rule)
//                          R/rest          when R/package.xml declares <name>PKG</name>
//                          R/D/rest        when R/D/package.xml declares <name>PKG</name>
//                                          (a package whose folder name differs from its name;
//                                          only the direct subfolders of R are looked at)
//   file://PATH          PATH absolute, or relative to the URDF file's folder
//   PATH                 a plain path: absolute, or relative to the URDF file's folder
// Every place looked at is recorded, so that a failure can list them all.
//
// A package folder is a boundary: a package:// path that leaves it, as written ("..") or once
// symbolic links are resolved (for a file that exists), is rejected with a message naming the URI
// and the folder. The lexical check comes before any file is looked at, so the message is the same
// whether or not a file exists outside. Only the first 64 KiB of a package.xml are read to find
// its <name>.

#include <string>
#include <vector>

namespace deepcheck::robots {

/// Outcome of resolving one URI.
struct UriResolution {
  std::string path;                   ///< absolute, normalized path of the file found ("" if none)
  std::vector<std::string> searched;  ///< every candidate looked at, in order
  std::string problem;                ///< why nothing was found ("" when found)
  bool rejected = false;              ///< the URI leaves its package folder (problem says so)
  bool found() const { return !path.empty(); }
};

/// The package roots to search for package:// URIs: `callerRoots` (in order), then the entries of
/// ROS_PACKAGE_PATH and the share/ folders of AMENT_PREFIX_PATH when `useEnvironment`. Empty
/// entries are skipped; duplicates are kept once.
std::vector<std::string> packageRoots(const std::vector<std::string>& callerRoots, bool useEnvironment = true);

/// Resolves `uri` (see the header comment). `roots` are the package roots (as returned by
/// packageRoots()); `baseDirectory` is the URDF file's folder, used for relative paths (may be
/// empty: then relative paths are relative to the current directory). Never throws for a missing
/// file: the result says what was searched.
UriResolution resolveUri(const std::string& uri, const std::vector<std::string>& roots,
                         const std::string& baseDirectory);

/// Same, but throws std::invalid_argument when nothing is found or the URI is rejected. The
/// message starts with `context` (e.g. "URDF 'panda.urdf', link 'panda_link3'"), then names the
/// URI and lists every place searched (or, when rejected, names the package folder it leaves).
std::string resolveUriOrThrow(const std::string& uri, const std::vector<std::string>& roots,
                              const std::string& baseDirectory, const std::string& context);

}  // namespace deepcheck::robots
