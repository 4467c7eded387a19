// Real collision meshes through robots' mesh loader and the convex decomposition: the Panda's
// links (from ../shared) are covered by their pieces and meet the target.

#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/robots/mesh_loader.h"

#include "decomposition/decomposition_test_util.h"
#include "robots_test_util.h"

#include <boost/test/unit_test.hpp>

#include <string>

namespace deepcheck::robots {

using decomposition::ConvexDecomposition;
using decomposition::ConvexPiece;
using decomposition::decomposeConvex;
using decomposition::test::checkDecomposition;

BOOST_AUTO_TEST_SUITE(robots_decomposition)

BOOST_AUTO_TEST_CASE(panda_links_are_covered_and_meet_the_target) {
  if (!test::haveShared("the Panda decomposition test")) return;
  const std::string folder = test::sharedDir() + "/robots/panda/moveit_resources_panda_description/meshes/collision/";
  for (const char* name : {"link0.stl", "hand.stl"}) {
    const TriangleMesh mesh = loadMesh(folder + name);
    const ConvexDecomposition d = decomposeConvex(mesh);
    checkDecomposition(mesh, d);
    for (const ConvexPiece& piece : d.pieces) BOOST_CHECK_LE(static_cast<int>(piece.vertices.size()), 64);
  }
}
BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
