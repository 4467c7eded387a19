// `deepcheck info ROBOT.urdf`: what deepcheck makes of a robot (or scene) description: its links
// with their collision elements and the convex pieces the checker uses (meshes decomposed through
// the same on-disk decomposition cache as `check` and `plan`, so a second run is quick; progress
// lines on stderr while a first decomposition runs long), the joints in configuration order with
// their limits, the meshes and how well their hulls fit them, and the self-collision pairs left
// after the pair filter (robots/include/deepcheck/robots/pair_filter.h), found on one convex hull
// per mesh.
//
// Output (stdout, plain text, one section per heading):
//   robot '<name>' (<file>)
//   <summary line: links, links with geometry, joints, variables, collision elements, pieces>
//   variables (configuration order):     one line per variable:
//     <index> <joint name> <type> <lower> <upper> <velocity limit>
//   mimic joints:                        "<joint> = <multiplier> * <variable> + <offset>" or none
//   locked joints:                       "<joint> (<URDF type>) held at <value>" or none (--group,
//                                        --lock)
//   links:                               one line per link, in link order:
//     <index> <link> <parent link> <parent joint> <collision elements> <pieces>
//                                        (<pieces>: the checker's, after decomposition)
//   pieces:                              one line per piece: <link> <kind> <vertices>
//   meshes (...):                        one line per distinct mesh file and scale
//   collision pairs (...):               the pair filter's counts
// With --write-srdf, the SRDF holds the disabled pairs and the planning groups: those of the
// --srdf files when given (with their virtual joints), else defaultChainGroup (robots/srdf.h).
// For a MoveIt planning scene (SCENE.yaml, .yml or .scene), the objects as read instead:
//   planning scene '<file>'
//   <objects> objects, <shapes> shapes, <attached> attached objects, <pairs> allowed pairs
//   objects (...):                       per object "<id> (frame <frame_id>, line <n>)", then
//     one line per shape: <name> <geometry> at <x y z> <qx qy qz qw> (its pose in the frame)
//   attached objects (...):              the same per attached object, after "on <link>"
//   allowed collisions:                  "<a> <b>" per allowed pair, "<name> anything" per
//                                        default entry, or none
// Units: metres, radians (limits of prismatic joints in metres), m/s or rad/s.

#include "common.h"
#include "load_world.h"
#include "subcommands.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kInfoUsage =
    "usage: deepcheck info ROBOT.urdf [--package-path DIR]... [--samples N] [--seed S]\n"
    "                      [--write-srdf FILE] [--srdf FILE... --group NAME] [--lock JOINT=VALUE]...\n"
    "       deepcheck info SCENE.yaml|SCENE.scene [--package-path DIR]...\n"
    "\n"
    "Describes a URDF robot or scene: links with their collision elements and the convex pieces\n"
    "the checker uses (meshes decomposed as by check and plan, through the same decomposition\n"
    "cache, so a second run is quick; progress on stderr while a first decomposition runs long),\n"
    "joints in configuration order with their limits, the collision meshes and how well their\n"
    "convex hulls fit them, and the self-collision pairs left after the pair filter (adjacent\n"
    "links, pairs colliding at the default configuration, always or never colliding in N random\n"
    "configurations, as MoveIt's setup assistant does; on one convex hull per mesh).\n"
    "A MoveIt planning scene (.yaml, .yml or .scene): its collision objects and attached objects\n"
    "as read, each with its frame and its shapes (geometry and pose in the object's frame,\n"
    "quaternions x y z w), and its allowed collisions.\n"
    "\n"
    "options:\n"
    "  --package-path DIR  a root to search for package:// URIs (repeatable; ROS_PACKAGE_PATH is\n"
    "                      also read)\n"
    "  --samples N         random configurations for the pair filter (default 10000; 0 skips the\n"
    "                      'Always' and 'Never' tests)\n"
    "  --seed S            seed of the random configurations (default 1)\n"
    "  --write-srdf FILE   write an SRDF file: the disabled pairs and the planning groups (those of\n"
    "                      --srdf, else a group 'manipulator': the chain from the root link to\n"
    "                      the end of the longest chain of moving joints)\n"
    "  --srdf FILE --group NAME\n"
    "                      describe the robot as planning group NAME of the SRDF moves it: its\n"
    "                      variables only, the other joints held (at --lock's value, else their\n"
    "                      default) and listed as locked; --srdf is repeatable (the files'\n"
    "                      groups are merged; a group two files define differently is an error)\n"
    "  --lock JOINT=VALUE  hold JOINT at VALUE (rad or m; repeatable)\n";

/// Volume enclosed by a closed, consistently wound mesh (divergence theorem); NaN otherwise.
double closedMeshVolume(const robots::TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  double volume6 = 0.0;
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
    volume6 += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  for (const auto& [edge, count] : edges) {
    const auto opposite = edges.find({edge.second, edge.first});
    if (opposite == edges.end() || opposite->second != count) {
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  return volume6 / 6.0;
}

/// Volume of a convex polytope from its faces (0 for points, segments and polygons).
double polytopeVolume(const geometry::ConvexPolytope& p) {
  if (p.kind() != geometry::PolytopeKind::Polyhedron) return 0.0;
  double volume6 = 0.0;
  const Eigen::Vector3d& c = p.center();
  for (int f = 0; f < p.numFaces(); ++f) {
    const geometry::IndexRange face = p.faceVertices(f);
    for (int k = 1; k + 1 < face.size(); ++k) {
      const Eigen::Vector3d a = p.vertex(face[0]) - c;
      const Eigen::Vector3d b = p.vertex(face[k]) - c;
      const Eigen::Vector3d d = p.vertex(face[k + 1]) - c;
      volume6 += a.dot(b.cross(d));
    }
  }
  return volume6 / 6.0;
}

std::string fileName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

void printMeshes(const robots::RobotModel& model) {
  // One line per distinct (file, scale), with the links that use it.
  struct Use {
    std::string path;
    Eigen::Vector3d scale;
    std::vector<std::string> links;
  };
  std::vector<Use> uses;
  for (const robots::Link& link : model.links()) {
    for (const robots::CollisionElement& c : link.collisions) {
      if (c.geometry.type != robots::GeometryType::Mesh) continue;
      bool found = false;
      for (Use& u : uses) {
        if (u.path == c.geometry.meshPath && u.scale == c.geometry.meshScale) {
          if (u.links.empty() || u.links.back() != link.name) u.links.push_back(link.name);
          found = true;
        }
      }
      if (!found) uses.push_back({c.geometry.meshPath, c.geometry.meshScale, {link.name}});
    }
  }
  std::printf("\nmeshes (hull: the convex hull of each mesh; the checker's pieces are in links):\n");
  if (uses.empty()) {
    std::printf("  none\n");
    return;
  }
  std::printf("  %-22s %9s %8s %12s %12s %9s %8s  %s\n", "mesh", "triangles", "vertices", "volume_m3", "hull_m3",
              "hull/mesh", "hull_vtx", "links");
  for (const Use& u : uses) {
    const robots::TriangleMesh mesh = robots::loadMesh(u.path, u.scale);
    const geometry::ConvexPolytope hull = geometry::ConvexPolytope::fromPoints(mesh.vertices, u.path);
    const double volume = closedMeshVolume(mesh);
    const double hullVolume = polytopeVolume(hull);
    std::string links;
    for (const std::string& l : u.links) links += (links.empty() ? "" : ",") + l;
    char ratio[32];
    if (std::isfinite(volume) && volume > 0.0) {
      std::snprintf(ratio, sizeof ratio, "%.3f", hullVolume / volume);
    } else {
      std::snprintf(ratio, sizeof ratio, "open");
    }
    std::printf("  %-22s %9zu %8zu %12.6g %12.6g %9s %8d  %s\n", fileName(u.path).c_str(), mesh.triangles.size(),
                mesh.vertices.size(), volume, hullVolume, ratio, hull.numVertices(), links.c_str());
  }
  std::printf(
      "  (hull/mesh > 1: the hull is larger than the mesh by that volume factor; 'open':\n"
      "  the mesh is not closed, so it has no volume)\n");
}

/// The command line of `deepcheck info`.
struct InfoArgs {
  std::string file;
  PackageRoots roots;
  robots::PairFilterOptions filter;
  std::string srdfPath;                 ///< --write-srdf
  bool pairFilterOptions = false;       ///< --samples, --seed or --write-srdf given
  std::vector<std::string> groupSrdfs;  ///< --srdf, in command-line order
  std::string group;                    ///< --group
  std::map<std::string, double> locks;  ///< --lock
};

InfoArgs takeInfoArgs(std::vector<std::string>& args) {
  InfoArgs a;
  a.roots = takePackageRoots(args);
  const std::string samplesText = takeSingleOption(args, "--samples");
  const std::string seedText = takeSingleOption(args, "--seed");
  a.srdfPath = takeSingleOption(args, "--write-srdf");
  a.groupSrdfs = takeOption(args, "--srdf");
  a.group = takeSingleOption(args, "--group");
  a.locks = takeLocks(args);
  if (a.group.empty() != a.groupSrdfs.empty()) {
    throw UsageError("--srdf and --group go together: the planning group NAME of the SRDF FILEs");
  }
  rejectUnknownOptions(args);
  if (args.size() != 1) {
    throw UsageError(args.empty() ? "missing ROBOT.urdf (or SCENE.yaml, SCENE.scene)"
                                  : "expected one file, got " + std::to_string(args.size()) + " arguments");
  }
  a.file = args[0];
  a.pairFilterOptions = !samplesText.empty() || !seedText.empty() || !a.srdfPath.empty();
  if (!samplesText.empty()) {
    a.filter.samples = static_cast<int>(parseCount(samplesText, "--samples", 0, std::numeric_limits<int>::max()));
  }
  if (!seedText.empty()) {
    a.filter.seed = parseCount(seedText, "--seed", 0, std::numeric_limits<std::uint64_t>::max());
  }
  return a;
}

void printSummary(const robots::RobotModel& model, const std::vector<std::vector<robots::CollisionPiece>>& pieces) {
  int geometryLinks = 0;
  int numPieces = 0;
  for (const auto& p : pieces) {
    geometryLinks += p.empty() ? 0 : 1;
    numPieces += static_cast<int>(p.size());
  }
  std::printf("robot '%s' (%s)\n", model.name().c_str(), model.source().c_str());
  std::printf(
      "%d links (%d with collision geometry), %d joints, %d variables, %d collision "
      "elements, %d convex pieces\n",
      model.numLinks(), geometryLinks, model.numJoints(), model.numVariables(), model.numCollisionElements(),
      numPieces);
}

void printJoints(const robots::RobotModel& model) {
  std::printf("\nvariables (configuration order):\n");
  std::printf("  %5s  %-24s %-10s %12s %12s %12s\n", "index", "joint", "type", "lower", "upper", "velocity");
  for (int v = 0; v < model.numVariables(); ++v) {
    const robots::Joint& j = model.joint(model.variableJoint(v));
    std::printf("  %5d  %-24s %-10s %12.6g %12.6g %12.6g\n", v, j.name.c_str(), toString(j.type),
                model.lowerLimits()[v], model.upperLimits()[v], j.velocityLimit);
  }
  std::printf("\nmimic joints:\n");
  bool anyMimic = false;
  for (const robots::Joint& j : model.joints()) {
    if (!j.isMimic()) continue;
    anyMimic = true;
    std::printf("  %s = %.6g * %s + %.6g\n", j.name.c_str(), j.multiplier, model.variableNames()[j.variable].c_str(),
                j.offset);
  }
  if (!anyMimic) std::printf("  none\n");
  std::printf("\nlocked joints:\n");
  bool anyLocked = false;
  for (const robots::Joint& j : model.joints()) {
    if (!j.locked) continue;
    anyLocked = true;
    std::printf("  %s (%s) held at %.17g\n", j.name.c_str(), j.urdfType.c_str(), j.lockedValue);
  }
  if (!anyLocked) std::printf("  none\n");
}

/// The convex pieces the checker uses for each link (by link index): those of a collision world
/// built with the default options, meshes decomposed through the default decomposition cache; the
/// world prints progress lines on stderr while this runs long.
std::vector<std::vector<robots::CollisionPiece>> checkerPieces(const robots::RobotModel& model) {
  const checker::World world(model);
  std::vector<std::vector<robots::CollisionPiece>> pieces(static_cast<std::size_t>(model.numLinks()));
  for (int l = 0; l < model.numLinks(); ++l) pieces[static_cast<std::size_t>(l)] = world.linkPieces(l);
  return pieces;
}

void printLinksAndPieces(const robots::RobotModel& model,
                         const std::vector<std::vector<robots::CollisionPiece>>& pieces) {
  std::printf("\nlinks:\n");
  std::printf("  %5s  %-24s %-24s %-24s %8s %6s\n", "index", "link", "parent", "joint", "elements", "pieces");
  for (int l = 0; l < model.numLinks(); ++l) {
    const robots::Link& link = model.link(l);
    std::printf("  %5d  %-24s %-24s %-24s %8zu %6zu\n", l, link.name.c_str(),
                link.parentLink < 0 ? "-" : model.link(link.parentLink).name.c_str(),
                link.parentJoint < 0 ? "-" : model.joint(link.parentJoint).name.c_str(), link.collisions.size(),
                pieces[l].size());
  }

  std::printf("\npieces:\n");
  bool anyPiece = false;
  for (int l = 0; l < model.numLinks(); ++l) {
    for (const robots::CollisionPiece& p : pieces[l]) {
      anyPiece = true;
      std::printf("  %-24s %-10s %4d vertices", model.link(l).name.c_str(), geometry::toString(p.core->kind()),
                  p.core->numVertices());
      if (p.radius > 0.0) std::printf(", radius %.6g", p.radius);
      std::printf("\n");
    }
  }
  if (!anyPiece) std::printf("  none\n");
}

void printCollisionPairs(const robots::RobotModel& model, const robots::PairFilterResult& result,
                         const robots::PairFilterOptions& filter) {
  std::printf("\ncollision pairs (pair filter: %d random samples, seed %llu):\n", result.samples,
              static_cast<unsigned long long>(filter.seed));
  std::printf("  links with geometry: %d, link pairs: %d\n", result.numGeometryLinks, result.numPairs());
  std::printf("  disabled: %zu (Adjacent %d, Default %d, Always %d, Never %d)\n", result.disabled.size(),
              result.count(robots::DisableReason::Adjacent), result.count(robots::DisableReason::Default),
              result.count(robots::DisableReason::Always), result.count(robots::DisableReason::Never));
  std::printf("  remaining (checked): %d\n", result.numEnabled());
  for (const robots::LinkPairReport& r : result.pairs) {
    if (r.reason) continue;
    std::printf("    %-24s %-24s collides in %d of %d samples\n", model.link(r.link1).name.c_str(),
                model.link(r.link2).name.c_str(), r.collisions, result.samples);
  }
}

/// The groups and virtual joints --write-srdf writes: those of the --srdf files, else a default
/// chain group.
robots::SrdfContents srdfContents(const robots::RobotModel& model, const robots::PairFilterResult& result,
                                  const InfoArgs& a) {
  robots::SrdfContents contents;
  contents.pairs = result.disabled;
  if (a.groupSrdfs.empty()) {
    contents.groups.push_back(robots::defaultChainGroup(model));
    return contents;
  }
  contents.groups = robots::readSrdfGroups(a.groupSrdfs);
  for (const std::string& srdf : a.groupSrdfs) {
    for (const robots::SrdfVirtualJoint& j : robots::readSrdfVirtualJoints(srdf)) contents.virtualJoints.push_back(j);
  }
  return contents;
}

void writeDisabledPairs(const robots::RobotModel& model, const robots::PairFilterResult& result, const InfoArgs& a) {
  const std::string comment = "Disabled collision pairs of " + model.name() + ", written by `deepcheck info " +
                              fileName(a.file) + "` (pair filter: robots/include/deepcheck/robots/pair_filter.h)\n" +
                              "     on the convex hull of each collision mesh, with " + std::to_string(result.samples) +
                              " random samples, seed " + std::to_string(a.filter.seed) + ".";
  const robots::SrdfContents contents = srdfContents(model, result, a);
  robots::writeSrdf(a.srdfPath, model.name(), contents, comment);
  std::printf("\nwrote %s (%zu disabled pairs, %zu planning groups)\n", a.srdfPath.c_str(), result.disabled.size(),
              contents.groups.size());
}

/// "box 0.3 x 0.3 x 0.6 m", "sphere radius 0.1 m", ...
std::string describe(const robots::SceneShape& shape) {
  const robots::Geometry& g = shape.geometry;
  char text[160];
  switch (g.type) {
    case robots::GeometryType::Box:
      std::snprintf(text, sizeof text, "box %.6g x %.6g x %.6g m", g.boxSize.x(), g.boxSize.y(), g.boxSize.z());
      return text;
    case robots::GeometryType::Sphere:
      std::snprintf(text, sizeof text, "sphere radius %.6g m", g.radius);
      return text;
    case robots::GeometryType::Cylinder:
      std::snprintf(text, sizeof text, "cylinder length %.6g m radius %.6g m", g.length, g.radius);
      return text;
    default:
      if (shape.mesh) return "in-memory mesh";
      std::snprintf(text, sizeof text, " scale %.6g %.6g %.6g", g.meshScale.x(), g.meshScale.y(), g.meshScale.z());
      return "mesh " + g.meshPath + text;
  }
}

/// "<id> (frame <frame>, line <n>)<suffix>", then one line per shape.
void printSceneObject(const robots::SceneObject& o, const std::string& suffix) {
  std::printf("  %s (frame %s, line %d)%s\n", o.id.c_str(), o.frameId.c_str(), o.line, suffix.c_str());
  for (const robots::SceneShape& shape : o.shapes) {
    const Eigen::Vector3d p = shape.X_FS.translation();
    const Eigen::Quaterniond q(shape.X_FS.rotation());
    std::printf("    %-34s %s at %.6g %.6g %.6g  %.6g %.6g %.6g %.6g\n", shape.name.c_str(), describe(shape).c_str(),
                p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
  }
}

int describePlanningScene(const InfoArgs& a) {
  if (a.pairFilterOptions || !a.group.empty() || !a.locks.empty()) {
    throw UsageError("--samples, --seed, --write-srdf, --group and --lock describe robots, not planning scenes");
  }
  robots::SceneLoadOptions load;
  load.packageRoots = a.roots.commandLine;
  const robots::PlanningScene scene = robots::loadPlanningScene(a.file, load);
  std::size_t shapes = 0;
  for (const robots::SceneObject& o : scene.objects) shapes += o.shapes.size();
  std::printf("planning scene '%s'\n%zu objects, %zu shapes, %zu attached objects, %zu allowed pairs\n",
              scene.source.c_str(), scene.objects.size(), shapes, scene.attached.size(), scene.allowed.pairs.size());
  std::printf("\nobjects (shape poses in the object's frame: x y z, quaternion qx qy qz qw):\n");
  for (const robots::SceneObject& o : scene.objects) printSceneObject(o, "");
  if (!scene.attached.empty()) std::printf("\nattached objects (touch links after 'touching'):\n");
  for (const robots::AttachedObject& a : scene.attached) {
    std::string touching;
    for (const std::string& l : a.touchLinks) touching += " " + l;
    printSceneObject(a.object, " on " + a.linkName + (touching.empty() ? "" : ", touching" + touching));
  }
  std::printf("\nallowed collisions:\n");
  for (const auto& [x, y] : scene.allowed.pairs) std::printf("  %s %s\n", x.c_str(), y.c_str());
  for (const std::string& name : scene.allowed.always) std::printf("  %s anything\n", name.c_str());
  if (scene.allowed.pairs.empty() && scene.allowed.always.empty()) std::printf("  none\n");
  return 0;
}

int runInfo(std::vector<std::string> args) {
  const InfoArgs a = takeInfoArgs(args);
  if (isPlanningSceneFile(a.file)) return describePlanningScene(a);
  robots::LoadOptions load;
  load.packageRoots = a.roots.commandLine;
  const robots::RobotModel model =
      robots::planningGroupModel(robots::RobotModel::fromUrdfFile(a.file, load), a.groupSrdfs, a.group, a.locks);
  const std::vector<std::vector<robots::CollisionPiece>> pieces = checkerPieces(model);
  printSummary(model, pieces);
  printJoints(model);
  printLinksAndPieces(model, pieces);
  printMeshes(model);
  // The pair filter works on one hull per mesh, as the SRDF written says.
  const robots::PairFilterResult result = robots::computeDisabledPairs(model, robots::collisionPieces(model), a.filter);
  printCollisionPairs(model, result, a.filter);
  if (!a.srdfPath.empty()) writeDisabledPairs(model, result, a);
  return 0;
}

}  // namespace

const Subcommand kInfoCommand = {"info", "describe a URDF robot (links, joints, pieces, pairs) or a planning scene",
                                 kInfoUsage, runInfo};

}  // namespace deepcheck::tools
