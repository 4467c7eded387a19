// End-to-end tests of `deepcheck decompose`: an L-shaped prism written as OBJ (not convex: it
// needs two pieces), the quality report and the OBJ of the pieces, the cache through the
// scratch folder, and the command-line errors.

#include "tool_runner.h"

#include <boost/test/unit_test.hpp>

#include <array>
#include <string>
#include <vector>

using namespace deepcheck::tool_test;

namespace {

/// The L-shaped polygon [0,2]x[0,1] U [0,1]x[0,2] (counter-clockwise) extruded from z = 0 to 1,
/// a closed, outward-wound OBJ mesh.
std::string lPrismObj() {
  const std::array<std::array<int, 2>, 6> corners = {{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}};
  std::string obj;
  for (int z = 0; z < 2; ++z) {
    for (const auto& c : corners)
      obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(z) + "\n";
  }
  // Vertex i at the bottom is i + 1 (OBJ is 1-based), at the top i + 7.
  auto face = [&obj](int a, int b, int c) {
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
  };
  for (const auto& [a, b, c] : {std::array<int, 3>{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}) {
    face(a + 7, b + 7, c + 7);  // top, normal +z
    face(a + 1, c + 1, b + 1);  // bottom, normal -z
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    face(i + 1, j + 1, j + 7);
    face(i + 1, j + 7, i + 7);
  }
  return obj;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_decompose)

BOOST_AUTO_TEST_CASE(l_prism_report_pieces_and_cache) {
  Scratch s;
  const std::string mesh = s.write("l.obj", lPrismObj());
  const std::string out = s.path("pieces.obj");
  Run r = s.run("decompose " + quote(mesh) + " --out " + quote(out) + " --max-pieces 8");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(contains(r.out, "triangles 20 vertices 12 components 1"), r.out);
  BOOST_TEST(contains(r.out, ": met\n"), r.out);
  BOOST_TEST(contains(r.out, "already convex: no"), r.out);
  BOOST_TEST(contains(r.out, "(cache stored;"), r.out);
  BOOST_TEST(contains(r.out, "wrote " + out), r.out);
  const std::string pieces = readText(out);
  BOOST_TEST(contains(pieces, "o piece_0"));
  BOOST_TEST(contains(pieces, "o piece_1"), "an L needs two pieces");

  // The table of several meshes: the same mesh twice is read back from the cache.
  r = s.run("decompose --report " + quote(mesh) + " " + quote(mesh) + " --max-pieces=8");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(contains(r.out, "meshes 2, target met by all: yes"), r.out);
  BOOST_TEST(contains(r.out, "cached load: 2 of 2 meshes from the cache"), r.out);
  // Other parameters are another cache entry; --no-cache neither reads nor writes.
  r = s.run("decompose " + quote(mesh) + " --no-cache");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(contains(r.out, "(cache not used;"), r.out);
}

BOOST_AUTO_TEST_CASE(command_line_errors) {
  Scratch s;
  const std::string mesh = quote(s.write("l.obj", lPrismObj()));
  for (const std::string& args :
       {std::string(""), mesh + " " + mesh, "--report " + mesh + " --out x.obj", mesh + " --cache c --no-cache",
        mesh + " --max-pieces 0", mesh + " --max-pieces 1000001", mesh + " --max-pieces 2.5",
        mesh + " --max-vertices -4", mesh + " --max-concavity x", mesh + " --max-concavity inf",
        mesh + " --min-concavity-abs 1e999", mesh + " --out a.obj --out b.obj", mesh + " --frobnicate"}) {
    const Run r = s.run("decompose " + args);
    BOOST_TEST(r.status == 2, "args '" << args << "': " << r.err);
    BOOST_TEST(contains(r.err, "usage: deepcheck decompose"), r.err);
  }
  const Run r = s.run("decompose " + mesh + " --max-pieces x");
  BOOST_TEST(contains(r.err, "option --max-pieces needs a whole number from 1 to 1000000, got 'x'"), r.err);
  // A missing mesh: exit 1, naming it.
  const Run missing = s.run("decompose " + quote(s.path("none.obj")));
  BOOST_TEST(missing.status == 1);
  BOOST_TEST(contains(missing.err, "none.obj"), missing.err);
}

BOOST_AUTO_TEST_SUITE_END()
