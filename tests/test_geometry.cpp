// Grooms (scenes/groom.h): guides and the generation rule (scenes/groom_rule.h),
// crowds (instances=), and render --geometry compute, which makes the same strands
// on the device as the CPU does (docs/geometry.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "base/errors.h"
#include "harness/checks.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "scenes/groom_rule.h"
#include "scenes/scene.h"
#include "tests/gpu_test_util.h"

namespace {

sb::Scene scene(const std::string& spec) { return sb::makeScene(sb::Spec::parse(spec)); }

bool sameBytes(const sb::Strands& a, const sb::Strands& b) {
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
  };
  return same(a.firstPoint, b.firstPoint) && same(a.pointCount, b.pointCount) &&
         same(a.points, b.points) && same(a.colors, b.colors) && same(a.thickness, b.thickness) &&
         same(a.transparency, b.transparency);
}

constexpr const char* kGroom = "straight:strands=96,points=8,seed=3,head=0";

// The hash is lowbias32: pinned values, so that a change to it (which the GLSL
// would follow) is seen.
TEST(GroomRule, HashAndUnitArePinned) {
  using namespace sb::groom_rule;
  EXPECT_EQ(groomHash(0u), 0u);
  EXPECT_EQ(groomHash(1u), 0x688990c0u);
  EXPECT_EQ(groomHash(12345u), 0x912efcf7u);
  EXPECT_NE(groomHash(1u), groomHash(2u));
  EXPECT_EQ(groomUnit(0xffffffffu), 16777215.0f / 16777216.0f);
  EXPECT_EQ(groomUnit(0u), 0.0f);
}

// Every strand its own guide and no variation: the rule gives the strands back
// bit for bit (the control of the tests below, which see them change).
TEST(GroomRule, WithoutVariationTheStrandsComeBackUnchanged) {
  const sb::Scene plain = scene(kGroom);
  const sb::Scene copy =
      scene(std::string(kGroom) + ",guides=1,guide_spread=0,guide_offset=0,noise=0");
  ASSERT_FALSE(copy.groom.empty());
  EXPECT_EQ(copy.groom.guideCount, 96u);
  EXPECT_TRUE(sameBytes(plain.strands, copy.strands));
  // With variation they move.
  const sb::Scene varied = scene(std::string(kGroom) + ",guides=1");
  EXPECT_FALSE(sameBytes(plain.strands, varied.strands));
}

TEST(GroomRule, GuidesMakeAsManyStrandsDeterministicallyAndTheSeedMatters) {
  const std::string spec = std::string(kGroom) + ",guides=8,clump=0.5";
  const sb::Scene a = scene(spec), b = scene(spec);
  EXPECT_EQ(a.groom.guideCount, 12u);
  EXPECT_EQ(a.strands.strandCount(), 96u);
  EXPECT_EQ(a.strands.points.size(), 96u * 8u);
  EXPECT_TRUE(sameBytes(a.strands, b.strands));
  // seed= changes the generator's strands too: compare the rule alone on one groom.
  sb::Groom g = a.groom;
  const sb::Strands one = sb::generateStrands(g);
  g.instanceSeeds[0] ^= 1u;
  EXPECT_FALSE(sameBytes(one, sb::generateStrands(g)));
  // Every root lies near its home guide's (within spread, offset and guide spacing).
  for (uint32_t i = 0; i < 96; ++i) {
    const glm::vec3 root = a.strands.points[i * 8];
    const glm::vec3 home(a.groom.guidePoints[(i % 12) * 8]);
    EXPECT_LT(glm::length(root - home), 1.0f) << "strand " << i;
  }
}

// clump=1 without noise: every tip is its home guide's tip.
TEST(GroomRule, FullClumpingBringsTheTipsToTheGuide) {
  const sb::Scene s = scene(std::string(kGroom) + ",guides=8,clump=1,noise=0");
  const sb::Scene loose = scene(std::string(kGroom) + ",guides=8,clump=0,noise=0");
  double clumped = 0, control = 0;
  for (uint32_t i = 0; i < 96; ++i) {
    const glm::vec3 tip(s.groom.guidePoints[(i % 12) * 8 + 7]);
    clumped = std::max(clumped, double(glm::length(s.strands.points[i * 8 + 7] - tip)));
    control = std::max(control, double(glm::length(loose.strands.points[i * 8 + 7] - tip)));
  }
  EXPECT_LT(clumped, 1e-5);
  EXPECT_GT(control, 1e-2);
}

// A crowd: N copies, each a rigid turn and move of the groom (no guides: no
// variation), side by side, and the scene's bounds hold them all.
TEST(GroomRule, InstancesAreRigidCopiesSideBySide) {
  const sb::Scene one = scene(kGroom);
  const sb::Scene crowd = scene(std::string(kGroom) + ",instances=4");
  ASSERT_EQ(crowd.strands.strandCount(), 4u * 96u);
  ASSERT_EQ(crowd.groom.instanceCount(), 4u);
  for (uint32_t k = 0; k < 4; ++k)
    for (uint32_t p = 0; p + 1 < 96u * 8u; p += 37) {
      const float d0 = glm::length(one.strands.points[p + 1] - one.strands.points[p]);
      const float dk =
          glm::length(crowd.strands.points[k * 768 + p + 1] - crowd.strands.points[k * 768 + p]);
      EXPECT_NEAR(dk, d0, 1e-5f) << "instance " << k;
    }
  const float r1 = one.bounds().radius(), r4 = crowd.bounds().radius();
  EXPECT_GT(r4, 1.8f * r1);  // a 2x2 grid spaced 1.25 extents apart
  // Instances differ (their own seeds turn them).
  EXPECT_NE(crowd.strands.points[0], crowd.strands.points[768]);
  // The file scenes take it too.
  EXPECT_EQ(crowd.mesh.positions.size(), 0u);
  const sb::Scene heads = scene("straight:strands=16,points=4,instances=3");
  EXPECT_EQ(heads.mesh.positions.size(),
            3 * scene("straight:strands=16,points=4").mesh.positions.size());
}

// lod=F keeps the first F of each instance's strands, every guide followed by
// some, their thickness widened by 1/F; lod=1 is the full groom (the control).
TEST(GroomRule, LevelOfDetailKeepsAShareOverEveryGuideAndWidensIt) {
  const std::string spec = std::string(kGroom) + ",guides=8,instances=2";
  const sb::Scene full = scene(spec), half = scene(spec + ",lod=0.25");
  EXPECT_EQ(full.strands.strandCount(), 2u * 96u);
  EXPECT_EQ(half.strands.strandCount(), 2u * 24u);
  EXPECT_EQ(half.strands.thickness[0], 4.0f * full.strands.thickness[0]);
  EXPECT_EQ(full.strands.thickness[0], full.groom.guidePoints[0].w);
  // The kept strands are the full groom's first ones, made alike.
  EXPECT_EQ(std::memcmp(half.strands.points.data(), full.strands.points.data(), 24 * 8 * 12), 0);
  std::vector<int> followers(12, 0);
  for (uint32_t i = 0; i < 24; ++i) ++followers[i % half.groom.guideCount];
  for (int n : followers) EXPECT_EQ(n, 2);
  EXPECT_THROW(scene(spec + ",lod=0"), sb::InputError);
  EXPECT_THROW(scene(std::string(kGroom) + ",lod=0.5"), sb::InputError);  // needs guides=
}

TEST(GroomRule, BadOptionsAreRefused) {
  EXPECT_THROW(scene(std::string(kGroom) + ",guide_spread=0.2"), sb::InputError);  // needs guides=
  EXPECT_THROW(scene(std::string(kGroom) + ",instances=0"), sb::InputError);
  EXPECT_THROW(scene(std::string(kGroom) + ",guides=2,clump=2"), sb::InputError);
  EXPECT_THROW(scene("straight:strands=1000,points=2000,head=0,instances=200"), sb::InputError);
}

// --geometry compute: the device's strands are the CPU's, byte for byte, and so
// is the image, on both APIs.
class GeometryCompute : public sbtest::BackendTest {};

sb::RenderRequest request(const std::string& backend, const std::string& geometry,
                          const std::string& shadow, const std::string& oit) {
  sb::RenderRequest r;
  r.backend = backend;
  r.scene = std::string(kGroom) + ",guides=4,clump=0.3,instances=2";
  r.shadow = shadow;
  r.oit = oit;
  r.geometry = geometry;
  r.width = r.height = 48;
  r.warmup = 0;
  return r;
}

TEST_P(GeometryCompute, TheDeviceMakesTheCpusStrandsBitForBit) {
  const sb::Scene s =
      scene(std::string(kGroom) + ",guides=4,clump=0.3,noise=0.5,instances=3,lod=0.5");
  std::vector<std::vector<uint8_t>> buffers[2];
  for (int path = 0; path < 2; ++path) {
    sb::RenderRequest req = request(GetParam(), "cpu", "none", "none");
    sb::RenderSettings settings = sb::makeRenderSettings(req, s);
    settings.geometry = path ? sb::GeometryPath::Compute : sb::GeometryPath::Cpu;
    sb::Renderer r(*dev_, s, settings, sb::Spec::parse("none"), sb::Spec::parse("none"));
    r.renderFrame();
    const sb::GpuScene& g = r.gpuScene();
    buffers[path] = {dev_->readBuffer(g.points), dev_->readBuffer(g.colors),
                     dev_->readBuffer(g.segments)};
  }
  const char* names[] = {"points", "colors", "segments"};
  for (int b = 0; b < 3; ++b) {
    ASSERT_EQ(buffers[0][b].size(), buffers[1][b].size()) << names[b];
    std::size_t differ = 0;
    for (std::size_t i = 0; i < buffers[0][b].size(); i += 4)
      differ += std::memcmp(&buffers[0][b][i], &buffers[1][b][i], 4) != 0;
    EXPECT_EQ(differ, 0u) << names[b] << ": words that differ between the CPU and the device";
  }
}

TEST_P(GeometryCompute, TheImageIsTheSameAndTheJsonSaysThePath) {
  for (const auto& [shadow, oit] : std::vector<std::pair<std::string, std::string>>{
           {"shadowmap", "abuffer"}, {"osm", "wboit"}}) {
    const sb::RenderResult cpu = sb::runRender(request(GetParam(), "cpu", shadow, oit));
    const sb::RenderResult gen = sb::runRender(request(GetParam(), "compute", shadow, oit));
    EXPECT_EQ(gen.geometry, "compute");
    EXPECT_EQ(cpu.geometry, "cpu");
    EXPECT_EQ(sb::compareImages(cpu.image, gen.image).maxAbs, 0.0) << shadow << " + " << oit;
    // The pass ran: its preparation is listed.
    EXPECT_NE(std::find(gen.preparations.begin(), gen.preparations.end(), "scene.generate"),
              gen.preparations.end());
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, GeometryCompute, ::testing::Values("gl", "vulkan"));

TEST(GeometryRefusals, MeshAndAGroomlessComputeAreRefusedWithTheReason) {
  sb::RenderRequest r = request("gl", "mesh", "none", "none");
  try {
    sb::checkRenderRequest(r, false);
    ADD_FAILURE() << "--geometry mesh accepted";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh shaders"), std::string::npos) << e.what();
  }
  r.geometry = "compute";
  r.scene = kGroom;
  try {
    sb::checkRenderRequest(r, false);
    ADD_FAILURE() << "--geometry compute accepted a scene without a groom";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("guides="), std::string::npos) << e.what();
  }
  r.scene = std::string(kGroom) + ",guides=2";
  EXPECT_NO_THROW(sb::checkRenderRequest(r, false));  // the control
}

}  // namespace
