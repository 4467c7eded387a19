// Fuzz harness: a MoveIt planning-scene YAML document (the bytes, as text) through the robots
// loader (moveit_scene.h), then placed in the world through a two-link robot with the frame
// alias world=base. Bad input must end in std::invalid_argument naming the problem (the loader's
// documented error), never a crash or another exception; what loads must be well formed
// (positive finite sizes, rigid finite poses, attached objects' shapes too), and written back
// with writePlanningScene it must read back to as many objects, attached objects and shapes,
// else the harness aborts. Relative mesh paths are resolved against a folder that does not exist
// and no package root is searched, so no mesh file is found or opened.

#include "scene_support.h"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace robots = deepcheck::robots;
  const std::string yaml(reinterpret_cast<const char*>(data), size);
  robots::SceneLoadOptions options;
  options.useRosPackagePath = false;
  robots::PlanningScene scene;
  try {
    scene = robots::parsePlanningScene(yaml, "/nonexistent-deepcheck-fuzz", options, "fuzz.yaml");
  } catch (const std::invalid_argument&) {
    return 0;  // rejected input: the loader's documented error
  }
  try {
    deepcheck::fuzz::requireWellFormed(scene);
  } catch (const std::invalid_argument&) {
    // A frame that is no link of the robot: the documented error of shapeWorldPoses.
  }
  std::string written;
  try {
    written = robots::writePlanningScene(scene);
  } catch (const std::invalid_argument&) {
    return 0;  // a shape with no file form (documented)
  }
  const robots::PlanningScene again = robots::parsePlanningScene(written, "/", options, "written.yaml");
  deepcheck::fuzz::require(deepcheck::fuzz::sameCounts(scene, again), "writePlanningScene",
                           "the scene read back has other counts of objects or shapes");
  return 0;
}
