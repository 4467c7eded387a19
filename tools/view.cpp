// `deepcheck view`: writes one self-contained HTML page (viewer/html_view.h) showing
//   - a robot in its scenes at a configuration or along a path file (`deepcheck plan --out`),
//     with the closest pair of every frame;
//   - a mesh and its convex decomposition with the quality report (--decompose MESH);
//   - the shapes of a `deepcheck pd` case file, one frame per query, with the answer (--pd FILE).
// The page is built in memory and written only when everything was read and checked: on a bad
// input (an unknown link, a path line with the wrong number of values, a NaN) nothing is written.

#include "common.h"
#include "load_world.h"
#include "pd_input.h"
#include "subcommands.h"

#include "deepcheck/decomposition/cache.h"
#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/geometry/signed_distance.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/package_path.h"
#include "deepcheck/viewer/html_view.h"

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kViewUsage =
    "usage: deepcheck view --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...\n"
    "                      [--scene S.yaml]... [--frame-alias NAME=LINK]...\n"
    "                      [--srdf FILE]... [--group NAME] [--lock JOINT=VALUE]... [--package-path DIR]... [--config "
    "q1 ... qn | --path FILE]\n"
    "                      [--hide LINK]... [--step S] --out view.html\n"
    "       deepcheck view --decompose MESH [--package-path DIR]... --out view.html\n"
    "       deepcheck view --pd CASES.txt --out view.html\n"
    "\n"
    "Writes one self-contained HTML page (three.js inlined; works offline): original geometry\n"
    "shaded, convex pieces as wireframes, toggled per layer and per body; the closest pair of each\n"
    "frame (witness points, arrow along the normal: green = distance, red = penetration depth);\n"
    "a path animated with a slider and play button, its minimum signed distance plotted per frame\n"
    "and the worst frame marked. The URL hash #t=N or #t=end selects the frame shown first.\n"
    "\n"
    "options:\n" DEEPCHECK_WORLD_OPTIONS_HELP
    "  --config q1 ... qn  the configuration shown (default: the robot's default configuration)\n"
    "  --path FILE         a path, one configuration per line (the `deepcheck plan --out` format)\n"
    "  --hide LINK         start with this robot link hidden (repeatable)\n"
    "  --step S            frames are added along the path so that no joint moves more than S\n"
    "                      (rad or m) between frames; default 0.05, 0 for the waypoints only\n"
    "  --decompose MESH    show a mesh (STL, OBJ, DAE, package:// URI) and its convex pieces\n"
    "  --pd FILE           show the shapes and answers of a `deepcheck pd` case file\n"
    "  --out FILE          the page to write (required)\n";

std::vector<Eigen::VectorXd> readPathFile(const std::string& file, const robots::RobotModel& robot) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read the path file '" + file + "'");
  std::vector<Eigen::VectorXd> path;
  try {
    path = readConfigurations(in, robot);
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
  if (path.empty()) throw InputError(file + ": no configuration in the path file");
  return path;
}

viewer::ViewScene worldView(std::vector<std::string>& args) {
  const WorldArgs worldArgs = takeWorldArgs(args);
  const std::vector<double> config = takeVector(args, "--config");
  const std::string pathFile = takeSingleOption(args, "--path");
  viewer::WorldViewOptions options;
  options.hiddenLinks = takeOption(args, "--hide");
  if (const std::string step = takeSingleOption(args, "--step"); !step.empty()) {
    options.maxStep = parseValue(step, "--step");
    if (options.maxStep < 0.0) throw UsageError("--step must be >= 0, got " + step);
  }
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args.front() + "'");
  if (!config.empty() && !pathFile.empty()) throw UsageError("--config and --path exclude each other");

  const checker::World world = loadWorld(worldArgs);
  const robots::RobotModel& robot = world.robot();
  std::vector<Eigen::VectorXd> configurations;
  if (!pathFile.empty()) {
    configurations = readPathFile(pathFile, robot);
  } else if (!config.empty()) {
    if (static_cast<int>(config.size()) != robot.numVariables()) {
      throw InputError("--config has " + std::to_string(config.size()) + " values, robot '" + robot.name() + "' has " +
                       std::to_string(robot.numVariables()) + " variables");
    }
    configurations.push_back(
        Eigen::Map<const Eigen::VectorXd>(config.data(), static_cast<Eigen::Index>(config.size())));
  } else {
    configurations.push_back(robot.defaultConfiguration());
  }
  options.title = "deepcheck view: " + robot.name();
  options.caption = world.summary();
  if (!pathFile.empty())
    options.caption =
        "path " + pathFile + " (" + std::to_string(configurations.size()) + " waypoints)\n" + options.caption;
  return viewer::viewOfWorld(world, configurations, options);
}

/// The hull's faces as triangles (fans), for shading.
std::shared_ptr<robots::TriangleMesh> hullMesh(const geometry::ConvexPolytope& hull) {
  auto mesh = std::make_shared<robots::TriangleMesh>();
  mesh->vertices = hull.vertices();
  for (int f = 0; f < hull.numFaces(); ++f) {
    const geometry::IndexRange face = hull.faceVertices(f);
    for (int i = 2; i < face.size(); ++i) mesh->triangles.push_back({face[0], face[i - 1], face[i]});
  }
  return mesh;
}

viewer::ViewBody convexBody(const std::string& name, const std::string& layer, const geometry::ConvexPolytope& hull) {
  viewer::ViewBody body;
  body.name = name;
  body.layer = layer;
  viewer::ViewShape shape;
  shape.geometry.type = robots::GeometryType::Mesh;
  shape.mesh = hullMesh(hull);
  body.shapes.push_back(shape);
  body.pieces.push_back(robots::CollisionPiece{std::make_shared<const geometry::ConvexPolytope>(hull), 0.0,
                                               Eigen::Isometry3d::Identity(), name});
  return body;
}

viewer::ViewScene pdView(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read the case file '" + file + "'");
  PdInput input;
  try {
    input = readPdInput(in);
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
  if (input.queries.empty()) throw InputError(file + ": no query in the case file");
  for (const PdQuery& q : input.queries) {
    if (q.namesBody()) {
      throw InputError(file + ": line " + std::to_string(q.line) +
                       ": the viewer shows queries of shapes only; this query names a body");
    }
  }
  std::vector<std::string> idOf(input.shapes.size());
  for (const auto& [id, index] : input.ids) idOf[static_cast<std::size_t>(index)] = id;

  viewer::ViewScene scene;
  scene.title = "deepcheck view: " + file;
  scene.caption = "deepcheck pd cases " + file + ": " + std::to_string(input.queries.size()) +
                  " queries, one per frame.\nGreen ghost: B moved by -sd * normal (the answer's translation: "
                  "it touches A).";
  scene.valueName = "signed distance (m)";
  std::map<std::pair<int, std::string>, int> trackOf;  // (shape, role) -> track
  const auto track = [&](int shape, const std::string& role) {
    const auto key = std::make_pair(shape, role);
    if (const auto it = trackOf.find(key); it != trackOf.end()) return it->second;
    const std::string name =
        (role == "answer" ? "B answer" : role) + ": shape '" + idOf[static_cast<std::size_t>(shape)] + "'";
    scene.bodies.push_back(convexBody(name, role, input.shapes[static_cast<std::size_t>(shape)].hull));
    scene.bodies.back().track = scene.numTracks;
    return trackOf[key] = scene.numTracks++;
  };
  struct Answer {
    int a, b, answer;
    geometry::SignedDistanceResult r;
  };
  std::vector<Answer> answers;
  for (const PdQuery& q : input.queries) {
    const Answer answer{track(q.a, "shape A"), track(q.b, "shape B"), track(q.b, "answer"),
                        geometry::signedDistance(input.shapes[static_cast<std::size_t>(q.a)].hull, q.X_WA,
                                                 input.shapes[static_cast<std::size_t>(q.b)].hull, q.X_WB)};
    answers.push_back(answer);
  }
  for (std::size_t i = 0; i < answers.size(); ++i) {
    const PdQuery& q = input.queries[i];
    const Answer& a = answers[i];
    viewer::ViewFrame frame;
    frame.poses.assign(static_cast<std::size_t>(scene.numTracks), Eigen::Isometry3d::Identity());
    frame.hidden.assign(frame.poses.size(), true);
    Eigen::Isometry3d X_answer = q.X_WB;
    X_answer.pretranslate(-a.r.distance * a.r.normal);
    for (const auto& [t, X] :
         {std::make_pair(a.a, q.X_WA), std::make_pair(a.b, q.X_WB), std::make_pair(a.answer, X_answer)}) {
      frame.poses[static_cast<std::size_t>(t)] = X;
      frame.hidden[static_cast<std::size_t>(t)] = false;
    }
    frame.label = "query on line " + std::to_string(q.line);
    frame.hasContact = true;
    frame.contact = viewer::ViewContact{a.r.distance,
                                        a.r.pointA,
                                        a.r.pointB,
                                        a.r.normal,
                                        "A '" + idOf[static_cast<std::size_t>(q.a)] + "'",
                                        "B '" + idOf[static_cast<std::size_t>(q.b)] + "'"};
    frame.value = a.r.distance;
    scene.frames.push_back(std::move(frame));
  }
  return scene;
}

viewer::ViewScene decomposeView(const std::string& meshArg, const PackageRoots& packages) {
  const std::string path =
      robots::resolveUriOrThrow(meshArg, robots::packageRoots(packages.commandLine), "", "--decompose");
  auto mesh = std::make_shared<const robots::TriangleMesh>(robots::loadMesh(path));
  const decomposition::ConvexDecomposition d = decomposition::decomposeConvexCached(
      *mesh, decomposition::DecompositionParams(), decomposition::DecompositionCache(""));
  viewer::ViewScene scene;
  scene.title = "deepcheck view: " + meshArg;
  viewer::ViewBody body;
  body.name = meshArg;
  body.layer = "mesh";
  viewer::ViewShape shape;
  shape.geometry.type = robots::GeometryType::Mesh;
  shape.mesh = mesh;
  body.shapes.push_back(shape);
  for (std::size_t i = 0; i < d.pieces.size(); ++i) {
    body.pieces.push_back(robots::CollisionPiece{
        std::make_shared<const geometry::ConvexPolytope>(geometry::ConvexPolytope::fromPoints(d.pieces[i].vertices)),
        0.0, Eigen::Isometry3d::Identity(), "piece " + std::to_string(i)});
  }
  scene.bodies.push_back(std::move(body));
  scene.frames.emplace_back();
  const decomposition::DecompositionReport& r = d.report;
  char caption[512];
  std::snprintf(caption, sizeof caption,
                "%s\n%d triangles, %d pieces (at most %d vertices each)\nconcavity %.4g m = %.2f%% of the "
                "bounding-box diagonal %.4g m; target %.4g m: %s\nvolume ratio pieces / mesh: %s",
                meshArg.c_str(), r.numTriangles, r.numPieces, r.maxPieceVertices, r.concavity,
                100.0 * r.concavityRelative, r.diagonal, r.targetConcavity, r.targetMet ? "met" : "NOT met",
                r.meshClosed ? std::to_string(r.volumeRatio).c_str() : "mesh not closed");
  scene.caption = caption;
  return scene;
}

int runView(std::vector<std::string> args) {
  const std::string out = takeSingleOption(args, "--out");
  const std::string decompose = takeSingleOption(args, "--decompose");
  const std::string pd = takeSingleOption(args, "--pd");
  if (out.empty()) throw UsageError("option --out is required");
  if (!decompose.empty() && !pd.empty()) throw UsageError("--decompose and --pd exclude each other");
  viewer::ViewScene scene;
  if (!decompose.empty() || !pd.empty()) {
    const PackageRoots packages = takePackageRoots(args);
    rejectUnknownOptions(args);
    if (!args.empty()) throw UsageError("unexpected argument '" + args.front() + "'");
    scene = decompose.empty() ? pdView(pd) : decomposeView(decompose, packages);
  } else {
    scene = worldView(args);
  }
  viewer::writeHtmlView(scene, out);
  std::fprintf(stderr, "wrote %s: %zu bodies, %zu frames\n", out.c_str(), scene.bodies.size(), scene.frames.size());
  return 0;
}

}  // namespace

const Subcommand kViewCommand = {"view", "write an offline HTML page showing a robot, a path, pieces or pd cases",
                                 kViewUsage, runView};

}  // namespace deepcheck::tools
