// The stray scene's own tests, carried by its folder (a copied folder brings them along).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scenes/scene.h"
#include "scenes/view.h"
#include "tests/test_util.h"

namespace {

// A clump plus one strand nearer the default light than any clump strand (occupancy paper,
// Fig. 5a), at the offset asked for.
TEST(SceneStray, StrayStrandLiesBetweenTheLightAndTheClump) {
  const sb::Scene s =
      sb::makeScene(sb::Spec::parse("stray:strands=500,points=8,radius=0.1,offset=0.5"));
  ASSERT_EQ(s.strands.strandCount(), 501u);
  ASSERT_NO_FATAL_FAILURE(sbtest::expectWellFormed(s.strands));
  const sb::Light light = sb::fitLight(s.bounds(), sb::LightType::Directional);
  auto lightDepth = [&](std::size_t strand) {
    return glm::dot(s.strands.points[s.strands.firstPoint[strand]] - light.position,
                    light.direction);
  };
  float nearestClump = 1e30f;
  for (std::size_t i = 0; i + 1 < s.strands.strandCount(); ++i)
    nearestClump = std::min(nearestClump, lightDepth(i));
  EXPECT_LT(lightDepth(500), nearestClump);
  EXPECT_TRUE(s.mesh.positions.empty());
  const glm::vec3 root = s.strands.points[s.strands.firstPoint[500]];
  EXPECT_NEAR(std::hypot(root.x, root.z), 0.5f, 1e-5f);
}

}  // namespace
