// Mesh loading (STL ASCII/binary, OBJ, DAE units and up axis, scale, degenerate triangles) and the
// collision pieces of primitives and meshes.

#include "robots_test_util.h"

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace deepcheck::robots;
using deepcheck::geometry::ConvexPolytope;
using deepcheck::geometry::PolytopeKind;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::sharedDir;
using deepcheck::robots::test::TempDir;

namespace {

using Triangle = std::array<Eigen::Vector3d, 3>;

/// The 12 triangles of the cube [0, 1]^3, counter-clockwise seen from outside.
std::vector<Triangle> unitCube() {
  const auto P = [](int i) { return Eigen::Vector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1); };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Triangle> out;
  for (const auto& q : quads) {
    out.push_back({P(q[0]), P(q[1]), P(q[2])});
    out.push_back({P(q[0]), P(q[2]), P(q[3])});
  }
  return out;
}

std::string asciiStl(const std::vector<Triangle>& triangles) {
  std::ostringstream s;
  s.precision(17);
  s << "solid test\n";
  for (const Triangle& t : triangles) {
    s << " facet normal 0 0 0\n  outer loop\n";
    for (const Eigen::Vector3d& v : t) s << "   vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    s << "  endloop\n endfacet\n";
  }
  s << "endsolid test\n";
  return s.str();
}

/// Binary STL; `declared` overrides the triangle count in the header (to make a broken file).
std::string binaryStl(const std::vector<Triangle>& triangles, long declared = -1) {
  std::string out(80, ' ');
  const std::uint32_t n = static_cast<std::uint32_t>(declared >= 0 ? declared : triangles.size());
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (const Triangle& t : triangles) {
    float f[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) f[3 + 3 * k + c] = static_cast<float>(t[k][c]);
    }
    out.append(reinterpret_cast<const char*>(f), sizeof f);
    out.append(2, '\0');
  }
  return out;
}

/// Signed volume enclosed by a closed mesh (positive when its triangles face outwards).
double signedVolume(const TriangleMesh& m) {
  double v = 0.0;
  for (const auto& t : m.triangles) {
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  }
  return v;
}

bool hasVertex(const TriangleMesh& m, const Eigen::Vector3d& p, double tol) {
  for (const Eigen::Vector3d& v : m.vertices) {
    if ((v - p).norm() <= tol) return true;
  }
  return false;
}

/// Largest excess of `points` over the face planes of a solid polytope (<= 0: all inside).
double maxOutside(const ConvexPolytope& p, const std::vector<Eigen::Vector3d>& points) {
  double worst = -1e300;
  for (const Eigen::Vector3d& x : points) {
    double inside = -1e300;
    for (int f = 0; f < p.numFaces(); ++f) {
      inside = std::max(inside, p.faceNormal(f).dot(x) - p.faceOffset(f));
    }
    worst = std::max(worst, inside);
  }
  return worst;
}

const char* kDae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="millimeter" meter="0.001"/><up_axis>UP_AXIS</up_axis></asset>
  <library_geometries>
    <geometry id="g" name="g"><mesh>
      <source id="g-pos">
        <float_array id="g-pos-array" count="9">0 0 0 100 0 0 0 200 300</float_array>
        <technique_common><accessor source="#g-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#g-vtx" offset="0"/><p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="s" name="s">
      <node id="n" name="n"><translate>10 0 0</translate><instance_geometry url="#g"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";

std::string daeWithUpAxis(const std::string& axis) {
  std::string s = kDae;
  s.replace(s.find("UP_AXIS"), 7, axis);
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_meshes)

BOOST_AUTO_TEST_CASE(stl_ascii_and_binary) {
  TempDir dir;
  std::vector<Triangle> triangles = unitCube();
  // A collinear (zero-area) triangle and one with a repeated corner: both dropped.
  triangles.push_back({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(1, 1, 1)});
  triangles.push_back({Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)});
  for (const std::string& path : {dir.write("a.stl", asciiStl(triangles)), dir.write("b.stl", binaryStl(triangles))}) {
    BOOST_TEST_CONTEXT(path) {
      const TriangleMesh m = loadMesh(path);
      BOOST_TEST(m.source == path);
      BOOST_TEST(m.triangles.size() == 12u);
      BOOST_TEST(m.vertices.size() == 8u);  // welded, the unused (0.5, 0.5, 0.5) removed
      BOOST_TEST(signedVolume(m) == 1.0, boost::test_tools::tolerance(1e-12));
      BOOST_TEST(m.boundingBoxDiagonal() == std::sqrt(3.0), boost::test_tools::tolerance(1e-12));
    }
  }
}

BOOST_AUTO_TEST_CASE(scale_and_mirroring) {
  TempDir dir;
  const std::string path = dir.write("cube.stl", binaryStl(unitCube()));
  const TriangleMesh m = loadMesh(path, Eigen::Vector3d(2.0, 0.5, -1.0 / 3.0));
  BOOST_TEST(hasVertex(m, Eigen::Vector3d(2.0, 0.5, -1.0 / 3.0), 1e-15));
  // The mirror is re-wound: the volume stays positive.
  BOOST_TEST(signedVolume(m) == 1.0 / 3.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(obj_objects_are_merged) {
  TempDir dir;
  const std::string path = dir.write("two.obj",
                                     "o first\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
                                     "o second\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 5 6 7\n");
  const TriangleMesh m = loadMesh(path);
  BOOST_TEST(m.triangles.size() == 3u);  // the quad is triangulated
  BOOST_TEST(m.vertices.size() == 7u);
  BOOST_TEST(hasVertex(m, Eigen::Vector3d(0, 1, 1), 0.0));
}

BOOST_AUTO_TEST_CASE(dae_unit_honoured_up_axis_ignored) {
  TempDir dir;
  // The file is in millimetres with a node translation of 10 mm. Whatever its up axis says, the
  // coordinates come out as written, in metres (to float precision: assimp's matrices are float).
  for (const std::string axis : {"Z_UP", "Y_UP", "X_UP"}) {
    BOOST_TEST_CONTEXT(axis) {
      const TriangleMesh m = loadMesh(dir.write("t_" + axis + ".dae", daeWithUpAxis(axis)));
      BOOST_REQUIRE(m.vertices.size() == 3u);
      BOOST_TEST(hasVertex(m, Eigen::Vector3d(0.01, 0, 0), 1e-7));
      BOOST_TEST(hasVertex(m, Eigen::Vector3d(0.11, 0, 0), 1e-7));
      BOOST_TEST(hasVertex(m, Eigen::Vector3d(0.01, 0.2, 0.3), 1e-7));
    }
  }
}

BOOST_AUTO_TEST_CASE(shared_meshes_load) {
  if (!haveShared("shared_meshes_load")) return;
  int files = 0;
  for (const std::string sub : {"robots", "scenes"}) {
    for (const auto& entry : fs::recursive_directory_iterator(sharedDir() + "/" + sub)) {
      if (entry.path().extension() != ".stl") continue;
      BOOST_TEST_CONTEXT(entry.path().string()) {
        TriangleMesh m = loadMesh(entry.path().string());
        ++files;
        BOOST_TEST(!m.empty());
        const double diagonal = m.boundingBoxDiagonal();
        BOOST_TEST(diagonal > 0.01);  // metres: no link or scene part is under 1 cm
        BOOST_TEST(diagonal < 5.0);
        BOOST_TEST(removeDegenerateTriangles(m) == 0);  // already clean
      }
    }
  }
  BOOST_TEST(files == 25);  // 10 Panda, 7 UR5, 5 kitchen, 3 table_bars
}

BOOST_AUTO_TEST_CASE(primitive_pieces) {
  const std::string xml = R"(<robot name="prims"><link name="body">
    <collision><origin xyz="0.1 0.2 0.3" rpy="0.1 0.2 0.3"/><geometry><box size="0.2 0.4 0.6"/></geometry></collision>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
    <collision><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision>
  </link></robot>)";
  const RobotModel m = RobotModel::fromUrdfString(xml, "", {}, "prims.urdf");
  const auto pieces = linkCollisionPieces(m, 0);
  BOOST_REQUIRE(pieces.size() == 3u);

  BOOST_TEST((pieces[0].core->kind() == PolytopeKind::Polyhedron));
  BOOST_TEST(pieces[0].core->numVertices() == 8);
  BOOST_TEST(pieces[0].radius == 0.0);
  BOOST_TEST(pieces[0].X_LP.isApprox(m.link(0).collisions[0].X_LG, 0.0));
  BOOST_TEST(pieces[0].origin == "link body collision 0 box");
  BOOST_TEST(pieces[0].core->supportBruteForce(Eigen::Vector3d(1, 1, 1)) >= 0);
  const Eigen::Vector3d corner = pieces[0].core->vertex(pieces[0].core->supportBruteForce(Eigen::Vector3d(1, 1, 1)));
  BOOST_TEST((corner - Eigen::Vector3d(0.1, 0.2, 0.3)).norm() < 1e-15);

  BOOST_TEST((pieces[1].core->kind() == PolytopeKind::Point));
  BOOST_TEST(pieces[1].radius == 0.05);
  BOOST_TEST(pieces[1].core->vertex(0).norm() == 0.0);

  // The cylinder's prism contains the cylinder and sticks out by at most the tolerance.
  const ConvexPolytope& prism = *pieces[2].core;
  const int sides = cylinderSides(0.05, tol::kCylinderMaxDeviation);
  BOOST_TEST(prism.numVertices() == 2 * sides);
  BOOST_TEST(pieces[2].origin == "link body collision 2 cylinder (" + std::to_string(sides) + "-sided prism)");
  std::vector<Eigen::Vector3d> rim;
  for (int k = 0; k < 997; ++k) {
    const double a = 2 * M_PI * k / 997;
    for (double z : {-0.15, 0.0, 0.15}) rim.emplace_back(0.05 * std::cos(a), 0.05 * std::sin(a), z);
  }
  BOOST_TEST(maxOutside(prism, rim) <= 1e-15);
  double deviation = 0.0;
  for (const Eigen::Vector3d& v : prism.vertices()) {
    deviation = std::max(deviation, v.head<2>().norm() - 0.05);
    BOOST_TEST(std::abs(std::abs(v.z()) - 0.15) < 1e-15);
  }
  BOOST_TEST(deviation <= tol::kCylinderMaxDeviation);
  // ...and the side count is the smallest that does so.
  BOOST_TEST(0.05 / std::cos(M_PI / (sides - 1)) - 0.05 > tol::kCylinderMaxDeviation);
  BOOST_TEST(cylinderSides(1e-4, 1e-3) == tol::kCylinderMinSides);
  BOOST_TEST(cylinderSides(100.0, 1e-3) == tol::kCylinderMaxSides);
  checkThrows([] { cylinderSides(0.1, 0.0); }, {"maximum deviation"});
}

BOOST_AUTO_TEST_CASE(mesh_pieces_and_decomposer_hook) {
  TempDir dir;
  dir.write("meshes/cube.stl", binaryStl(unitCube()));
  const std::string urdf = dir.write("r.urdf", R"(<robot name="r">
  <link name="a"><collision><origin xyz="1 0 0"/><geometry><mesh filename="meshes/cube.stl" scale="0.1 0.2 0.3"/></geometry></collision></link>
  <link name="b"><collision><geometry><mesh filename="meshes/cube.stl" scale="0.1 0.2 0.3"/></geometry></collision></link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>)");
  const RobotModel m = RobotModel::fromUrdfFile(urdf, {});

  // Default: one convex hull per mesh, shared between the two uses.
  const auto all = collisionPieces(m);
  BOOST_REQUIRE(all.size() == 2u);
  BOOST_REQUIRE(all[0].size() == 1u);
  BOOST_REQUIRE(all[1].size() == 1u);
  BOOST_TEST(all[0][0].core == all[1][0].core);
  BOOST_TEST(all[0][0].core->numVertices() == 8);
  BOOST_TEST(all[0][0].origin == "link a collision 0 mesh cube.stl piece 0");
  BOOST_TEST((all[0][0].X_LP.translation() - Eigen::Vector3d(1, 0, 0)).norm() == 0.0);
  const TriangleMesh mesh = loadMesh(m.link(0).collisions[0].geometry.meshPath, Eigen::Vector3d(0.1, 0.2, 0.3));
  BOOST_TEST(maxOutside(*all[0][0].core, mesh.vertices) <= 1e-12);

  // A decomposer plugged in: called once per distinct mesh; its pieces are numbered.
  int calls = 0;
  CollisionGeometryOptions options;
  options.decomposer = [&calls](const TriangleMesh& mesh) {
    ++calls;
    std::vector<Eigen::Vector3d> low, high;
    for (const Eigen::Vector3d& v : mesh.vertices) {
      (v.z() < 0.15 ? low : high).push_back(v);
    }
    std::vector<ConvexPolytope> out;
    out.push_back(ConvexPolytope::fromPoints(low));
    out.push_back(ConvexPolytope::fromPoints(high));
    return out;
  };
  const auto split = collisionPieces(m, options);
  BOOST_TEST(calls == 1);
  BOOST_REQUIRE(split[1].size() == 2u);
  BOOST_TEST(split[1][1].origin == "link b collision 0 mesh cube.stl piece 1");
}

BOOST_AUTO_TEST_CASE(shared_pieces_cover_meshes) {
  if (!haveShared("shared_pieces_cover_meshes")) return;
  struct Case {
    std::string urdf, root;
    int elements;
  };
  const std::string scenes = "/scenes/motion_bench_maker/configs/scenes/";
  const std::vector<Case> cases{
      {"/robots/panda/moveit_resources_panda_description/urdf/panda.urdf", "/robots/panda", 11},
      {"/robots/ur5/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf", "/robots/ur5", 8},
      {scenes + "kitchen/kitchen.urdf", "/scenes", 5},
      {scenes + "table_bars/table_bars.urdf", "/scenes", 3}};
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.urdf) {
      LoadOptions o;
      o.packageRoots = {sharedDir() + c.root};
      o.useRosPackagePath = false;
      const RobotModel m = RobotModel::fromUrdfFile(sharedDir() + c.urdf, o);
      const auto pieces = collisionPieces(m);
      BOOST_REQUIRE(static_cast<int>(pieces.size()) == m.numLinks());
      int total = 0;
      for (int l = 0; l < m.numLinks(); ++l) {
        BOOST_TEST(pieces[l].size() == m.link(l).collisions.size());
        total += static_cast<int>(pieces[l].size());
        for (size_t i = 0; i < pieces[l].size(); ++i) {
          const CollisionPiece& p = pieces[l][i];
          BOOST_TEST((p.core->kind() == PolytopeKind::Polyhedron));
          const Geometry& g = m.link(l).collisions[i].geometry;
          if (g.type != GeometryType::Mesh) continue;
          // The default decomposer's hull contains every vertex of the mesh.
          const TriangleMesh mesh = loadMesh(g.meshPath, g.meshScale);
          BOOST_CHECK_MESSAGE(maxOutside(*p.core, mesh.vertices) <= 1e-9 * mesh.boundingBoxDiagonal(), p.origin);
        }
      }
      BOOST_TEST(total == c.elements);
      if (m.name() == "panda") {
        // Both fingers use finger.stl: one hull.
        BOOST_TEST(pieces[m.linkIndex("panda_leftfinger")][0].core == pieces[m.linkIndex("panda_rightfinger")][0].core);
      }
    }
  }
}

// ---- bad input ----

BOOST_AUTO_TEST_CASE(error_broken_stl) {
  TempDir dir;
  // A binary STL whose header promises 12 triangles but holds 5.
  std::vector<Triangle> cube = unitCube();
  const std::string path = dir.write("broken.stl", binaryStl({cube.begin(), cube.begin() + 5}, 12));
  checkThrows([&] { loadMesh(path); }, {path, "assimp", "declares 12 triangles", "truncated"});

  // Through a robot: the message also names the URDF, the link and the collision element.
  const std::string urdf = dir.write("r.urdf", R"(<robot name="r"><link name="gripper">
    <collision><geometry><mesh filename="broken.stl"/></geometry></collision></link></robot>)");
  const RobotModel m = RobotModel::fromUrdfFile(urdf, {});
  checkThrows([&] { collisionPieces(m); }, {urdf, "link 'gripper'", "collision 0", path});
}

BOOST_AUTO_TEST_CASE(error_empty_mesh) {
  TempDir dir;
  const std::string none = dir.write("none.stl", binaryStl({}));
  checkThrows([&] { loadMesh(none); }, {none});
  const std::string points = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  checkThrows([&] { loadMesh(points); }, {points, "no triangles"});
  const std::string flat =
      dir.write("flat.stl", asciiStl({{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, 2, 2)}}));
  checkThrows([&] { loadMesh(flat); }, {flat, "degenerate"});
  const std::string zero = dir.write("zero.stl", "");
  checkThrows([&] { loadMesh(zero); }, {zero, "assimp"});
}

BOOST_AUTO_TEST_CASE(error_one_line_obj) {
  TempDir dir;
  // assimp 5.2's OBJ reader hands atoi an unterminated string on these; the loader stops first.
  const std::string fuzzed = dir.write("fuzzed.obj",
                                       "l\xff\xff\xff\xff\xff"
                                       "2n><accessor \xff\xff\xff\xff\xff\xff\xff D/a>LL\n");
  checkThrows([&] { loadMesh(fuzzed); }, {"mesh file '" + fuzzed + "'", "one line", "OBJ 'l' statement"});
  const std::string face = dir.write("face.obj", "f 1 2 3 4 5 6 7 8 9");
  checkThrows([&] { loadMesh(face); }, {face, "OBJ 'f' statement"});
  const std::string led = dir.write("led.input", "\n\xEF\xBB\xBFp 1 2 3 4 5 6 7 8 9");
  checkThrows([&] { loadMesh(led); }, {led, "OBJ 'p' statement"});
  // Two line ends, or another first statement: assimp's to read or to report.
  const std::string two = dir.write("two.obj", "f 1 2 3 4 5 6 7 8 9\n\n");
  checkThrows([&] { loadMesh(two); }, {two, "assimp"});
  const std::string vertex = dir.write("vertex.obj", "v 0 0 0 1 2 3 4 5 6 7 8 9");
  checkThrows([&] { loadMesh(vertex); }, {vertex, "no triangles"});
}

std::string daeWithIndices(const std::string& indices) {
  std::string s = daeWithUpAxis("Z_UP");
  const std::string list = "<p>0 1 2</p>";
  s.replace(s.find(list), list.size(), "<p>" + indices + "</p>");
  return s;
}

BOOST_AUTO_TEST_CASE(error_collada_checks) {
  TempDir dir;
  // assimp 5.2 would loop on these, allocating until memory runs out, or crash; the loader stops
  // first.
  const std::string stray = dir.write("stray.dae", daeWithIndices(std::string("0 1 \x13 2")));
  checkThrows([&] { loadMesh(stray); }, {stray, "line 13", "<p>", "byte 0x13"});
  const std::string letter = dir.write("letter.dae", daeWithIndices("0 1 x"));
  checkThrows([&] { loadMesh(letter); }, {letter, "<p>", "'x' (0x78)"});
  const std::string negative = dir.write("negative.dae", daeWithIndices("0 -1 2"));
  checkThrows([&] { loadMesh(negative); }, {negative, "'-'"});
  const std::string cdata = dir.write("cdata.dae", daeWithIndices("<![CDATA[0 1 2]]>"));
  checkThrows([&] { loadMesh(cdata); }, {cdata, "<p>", "markup"});
  // Recognised by content, whatever the extension.
  const std::string byContent = dir.write("named.mesh", daeWithIndices("0 1 x"));
  checkThrows([&] { loadMesh(byContent); }, {byContent, "'x'"});

  // Arrays need their count, and an accessor must lie inside its array (assimp 5.2 crashed).
  std::string noCount = daeWithUpAxis("Z_UP");
  noCount.replace(noCount.find(" count=\"9\""), 10, "");
  const std::string uncounted = dir.write("uncounted.dae", noCount);
  checkThrows([&] { loadMesh(uncounted); }, {uncounted, "line 7", "<float_array> 'g-pos-array'", "no count"});
  std::string longer = daeWithUpAxis("Z_UP");
  longer.replace(longer.find("count=\"3\" stride"), 9, "count=\"4\"");
  const std::string beyond = dir.write("beyond.dae", longer);
  checkThrows([&] { loadMesh(beyond); }, {beyond, "line 8", "<accessor>", "4 x 3", "beyond the array's 9"});
  std::string empty = daeWithUpAxis("Z_UP");
  empty.replace(empty.find("count=\"9\""), 9, "count=\"0\"");
  const std::string zero = dir.write("zero.dae", empty);
  checkThrows([&] { loadMesh(zero); }, {zero, "beyond the array's 0"});
  std::string word = daeWithUpAxis("Z_UP");
  word.replace(word.find("count=\"9\""), 9, "count=\"nine\"");
  const std::string named = dir.write("word.dae", word);
  checkThrows([&] { loadMesh(named); }, {named, "count \"nine\""});

  // Whitespace of every XML kind is fine; a wrong count is still assimp's to report.
  const TriangleMesh spaced = loadMesh(dir.write("spaced.dae", daeWithIndices("\n\t0\r\n 1\t2 ")));
  BOOST_TEST(spaced.triangles.size() == 1u);
  const std::string short_ = dir.write("short.dae", daeWithIndices("0 1"));
  checkThrows([&] { loadMesh(short_); }, {short_, "assimp", "index count"});
}

BOOST_AUTO_TEST_CASE(error_missing_mesh_file_and_bad_scale) {
  TempDir dir;
  const std::string missing = (dir.path() / "gone.stl").string();
  checkThrows([&] { loadMesh(missing); }, {missing, "does not exist"});
  const std::string cube = dir.write("cube.stl", binaryStl(unitCube()));
  checkThrows([&] { loadMesh(cube, Eigen::Vector3d(1, 0, 1)); }, {cube, "scale"});
  checkThrows([&] { loadMesh(dir.path().string()); }, {"not a regular file"});
}

BOOST_AUTO_TEST_SUITE_END()
