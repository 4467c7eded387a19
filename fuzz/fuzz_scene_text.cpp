// Fuzz harness: MoveIt's .scene text (the bytes, as text) through parseSceneText (moveit_scene.h),
// then placed in the world through a two-link robot (kModelFrame is its root link). Bad input must
// end in std::invalid_argument naming the problem, never a crash or another exception; what loads
// must be well formed (positive finite sizes, rigid finite poses), and written back with
// writeSceneText it must read back to as many objects and shapes, else the harness aborts.

#include "scene_support.h"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace robots = deepcheck::robots;
  const std::string text(reinterpret_cast<const char*>(data), size);
  robots::PlanningScene scene;
  try {
    scene = robots::parseSceneText(text, {}, "fuzz.scene");
  } catch (const std::invalid_argument&) {
    return 0;  // rejected input: the reader's documented error
  }
  deepcheck::fuzz::requireWellFormed(scene);
  std::string written;
  try {
    written = robots::writeSceneText(scene);
  } catch (const std::invalid_argument&) {
    return 0;  // an id a .scene line cannot hold (documented)
  }
  const robots::PlanningScene again = robots::parseSceneText(written, {}, "written.scene");
  deepcheck::fuzz::require(deepcheck::fuzz::sameCounts(scene, again), "writeSceneText",
                           "the scene read back has other counts of objects or shapes");
  return 0;
}
