// voxel's own tests (picked up by the build from its folder, as techniques/*/test_*.cpp): the
// march shared with the GLSL (voxel_math.glsl compiled as C++) against the exact count on the
// CPU, and both backends against the exact visibility.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "harness/render.h"
#include "techniques/voxel/voxel_math.h"
#include "tests/gpu_test_util.h"

namespace sb {
namespace {

// --- the march (voxel_math.glsl) ---

struct Grid {
  int g;
  std::vector<float> counts;
  float& at(int x, int y, int s) { return counts[(s * g + y) * g + x]; }
  void use() {
    glsl::voxelCountsCpu = counts.data();
    glsl::voxelColumnsCpu = g;
  }
};

TEST(VoxelMath, MarchingTheWholeColumnCountsEveryFragment) {
  Grid grid{8, std::vector<float>(8 * 8 * 8, 0.0f)};
  grid.at(3, 4, 1) = 2;
  grid.at(3, 4, 5) = 3;
  grid.use();
  // At a voxel centre, steps = grid: the march sums the column's slices.
  for (const int steps : {8, 16, 64}) {
    EXPECT_NEAR(glsl::voxelHairCount(3, 4, 1.0f, 8, steps), 5.0f, 1e-4f) << steps;
    EXPECT_NEAR(glsl::voxelHairCount(3, 4, 0.0f, 8, steps), 0.0f, 1e-6f);
  }
  // Between the two slices: the first's count (slice 1 ends at 2/8).
  EXPECT_NEAR(glsl::voxelHairCount(3, 4, 0.5f, 8, 8), 2.0f, 1e-4f);
  // With density_scale 1 the visibility is (1 - alpha)^n.
  EXPECT_NEAR(glsl::voxelVisibility(5.0f, 0.3f, 1.0f), std::pow(0.7f, 5.0f), 1e-6f);
  EXPECT_EQ(glsl::voxelVisibility(5.0f, 0.3f, 0.0f), 1.0f);
  EXPECT_EQ(glsl::voxelVisibility(5.0f, 1.0f, 1.0f) >= 0.0f, true);
  // Half way into slice 5: slice 1's 2 and half of slice 5's 3 (the partial
  // step takes the density of its whole step's middle).
  EXPECT_NEAR(glsl::voxelHairCount(3, 4, 5.5f / 8.0f, 8, 8), 2.0f + 0.5f * 3.0f, 1e-4f);
  // The comparison fails on a wrong column.
  EXPECT_GT(std::abs(glsl::voxelHairCount(5, 4, 1.0f, 8, 8) - 5.0f), 1.0f);
}

TEST(VoxelMath, CountNeverFallsAlongTheRayAndStaysFinite) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const int g : {4, 16, 32}) {
    Grid grid{g, std::vector<float>(std::size_t(g) * g * g)};
    for (float& c : grid.counts) c = u(rng) < 0.3f ? std::floor(u(rng) * 20.0f) : 0.0f;
    grid.use();
    for (const int steps : {1, 7, g, 3 * g}) {
      const int cx = int(u(rng) * float(g - 1)), cy = int(u(rng) * float(g - 1));
      float prev = 0.0f;
      for (float z = -0.1f; z <= 1.1f; z += 1e-3f) {
        const float n = glsl::voxelHairCount(cx, cy, z, g, steps);
        ASSERT_TRUE(std::isfinite(n));
        ASSERT_GE(n, prev - 1e-4f * std::max(prev, 1.0f)) << g << " " << steps << " " << z;
        prev = n;
        const float v = glsl::voxelVisibility(n, 0.5f, 1.0f);
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
      }
    }
  }
}

// --- GPU: both backends against the exact visibility ---

class VoxelShadow : public sbtest::ProbedShadowTest {};

TEST_P(VoxelShadow, RendersWithinItsInvariantsAndGridHelps) {
  const RenderResult coarse = run(request("stray:strands=1500", "voxel:grid=16,steps=16,size=128"));
  const RenderResult fine = run(request("stray:strands=1500", "voxel:grid=64,steps=64,size=128"));
  EXPECT_GT(counter(fine, "voxel_fragments"), 0.0);
  EXPECT_EQ(counter(fine, "voxel_grid_bytes"), 64.0 * 64 * 64 * 4);
  EXPECT_GT(coarse.visibilityError->rmse, 0.0);
  EXPECT_LT(fine.visibilityError->rmse, coarse.visibilityError->rmse);
  // density_scale 0: no shadow from the hair at all, a larger error.
  const RenderResult none =
      run(request("stray:strands=1500", "voxel:grid=64,density_scale=0,size=128"));
  EXPECT_GT(none.visibilityError->rmse, fine.visibilityError->rmse);
}

TEST_P(VoxelShadow, BadOptionsAreRejectedNamingThem) {
  for (const auto& [shadow, name] : std::vector<std::pair<std::string, std::string>>{
           {"voxel:grid=1000", "grid"},
           {"voxel:steps=0", "steps"},
           {"voxel:density_scale=-1", "density_scale"}})
    sbtest::expectInputError([&] { runRender(request("straight:strands=10", shadow)); }, {name});
}

INSTANTIATE_TEST_SUITE_P(Backends, VoxelShadow, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

TEST(VoxelShadowInvariants, PromisesToFall) {
  EXPECT_TRUE(makeShadowTechnique(Spec::parse("voxel"))->monotone());
}

// GL and Vulkan render it alike (visibility within 1e-4).
TEST(VoxelShadowParity, GlAndVulkanAgree) {
  const sbtest::BothBackends both = sbtest::makeBothBackends();
  if (!both.unavailable.empty()) GTEST_SKIP() << both.unavailable;
  sbtest::expectShadowParity(both, {"voxel:size=128,grid=64,steps=64"});
}

}  // namespace
}  // namespace sb
