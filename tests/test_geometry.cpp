// Grooms (scenes/groom.h): guides and the generation rule (scenes/groom_rule.h),
// crowds (instances=), and render --geometry compute, which makes the same strands
// on the device as the CPU does (docs/geometry.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/errors.h"
#include "harness/checks.h"
#include "harness/measures/lod/lod.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "scenes/groom_rule.h"
#include "scenes/scene.h"
#include "scenes/view.h"
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

// The scene as a view with camera `cam` (default: fitted to the full model,
// 64 pixels high) draws it: lod= and lod_pixels= choose the strands there.
sb::Scene drawn(const sb::Scene& full, uint32_t height = 64,
                std::optional<sb::Camera> cam = std::nullopt) {
  return sb::withLevelOfDetail(full, cam ? *cam : sb::fitCamera(full.bounds(), 1.0f), height);
}

// The index of each strand of `part` in `full` (by its root, which the rule makes
// alike in both), or -1 where it is none of them.
std::vector<int> whichStrands(const sb::Strands& part, const sb::Strands& full) {
  std::vector<int> out;
  for (std::size_t a = 0; a < part.strandCount(); ++a) {
    int found = -1;
    for (std::size_t b = 0; b < full.strandCount() && found < 0; ++b)
      if (part.pointCount[a] == full.pointCount[b] &&
          std::memcmp(&part.points[part.firstPoint[a]], &full.points[full.firstPoint[b]],
                      sizeof(glm::vec3) * part.pointCount[a]) == 0)
        found = int(b);
    out.push_back(found);
  }
  return out;
}

// lod=F keeps round(F * strands) of each instance's strands: whole rows of
// followers (one of each guide) and, of the row cut short, guides spread by the
// guide order; the kept strands are the full groom's own, widened by strands /
// kept, and a smaller share keeps a subset of a larger one. makeScene makes the
// full model (the camera and the full model's reference use it); lod=1 is it.
TEST(GroomRule, LevelOfDetailKeepsAShareOverEveryGuideAndWidensIt) {
  const std::string spec = std::string(kGroom) + ",guides=8,instances=2";
  const sb::Scene full = scene(spec);
  const sb::Scene quarter = drawn(scene(spec + ",lod=0.25"));
  const sb::Scene tenth = drawn(scene(spec + ",lod=0.1"));
  EXPECT_EQ(full.strands.strandCount(), 2u * 96u);
  EXPECT_EQ(scene(spec + ",lod=0.25").strands.strandCount(), 2u * 96u);  // the full model
  EXPECT_EQ(quarter.strands.strandCount(), 2u * 24u);
  EXPECT_EQ(tenth.strands.strandCount(), 2u * 10u);
  EXPECT_TRUE(sameBytes(drawn(scene(spec + ",lod=1")).strands, full.strands));  // the control
  // Kept strands are the full groom's own; 0.1's are among 0.25's.
  const std::vector<int> q = whichStrands(quarter.strands, full.strands);
  const std::vector<int> t = whichStrands(tenth.strands, full.strands);
  for (int i : q) EXPECT_GE(i, 0);
  ASSERT_GE(t[0], 0);
  EXPECT_EQ(quarter.strands.thickness[0], 4.0f * full.strands.thickness[q[0] * 8]);
  EXPECT_EQ(tenth.strands.thickness[0], 9.6f * full.strands.thickness[t[0] * 8]);
  EXPECT_EQ(full.strands.thickness[0], full.groom.guidePoints[0].w);
  for (int i : t) EXPECT_NE(std::find(q.begin(), q.end(), i), q.end()) << "strand " << i;
  // 24 of 96 with 12 guides: two whole rows, every guide followed twice.
  std::vector<int> followers(12, 0);
  for (int i = 0; i < 24; ++i) ++followers[q[i] % 96 % 12];
  for (int n : followers) EXPECT_EQ(n, 2);
  // 10 of 96: no whole row; ten different guides, not the first ten.
  std::vector<int> homes;
  for (int i = 0; i < 10; ++i) homes.push_back(t[i] % 96 % 12);
  std::sort(homes.begin(), homes.end());
  EXPECT_EQ(std::unique(homes.begin(), homes.end()), homes.end());
  EXPECT_NE(homes.back(), 9);
  EXPECT_THROW(scene(spec + ",lod=0"), sb::InputError);
  EXPECT_THROW(scene(spec + ",lod=0.5,lod_pixels=20"), sb::InputError);  // one or the other
  // Without guides every strand is its own guide: a share of the strands, unchanged.
  const sb::Scene plain = scene(kGroom), half = drawn(scene(std::string(kGroom) + ",lod=0.5"));
  EXPECT_EQ(half.strands.strandCount(), 48u);
  for (int i : whichStrands(half.strands, plain.strands)) EXPECT_GE(i, 0);
}

// lod_pixels=P: an instance spanning s pixels keeps min(1, (s/P)^2) of its
// strands, so the share falls with the distance to the camera; the same camera
// gives the same strands (deterministic), a farther one fewer.
TEST(GroomLod, TheShareFollowsTheDistanceToTheCamera) {
  const sb::Scene full = scene(std::string(kGroom) + ",guides=8,instances=9,lod_pixels=64");
  const sb::Camera cam = sb::fitCamera(full.bounds(), 1.0f);
  const sb::Groom& g = drawn(full, 128, cam).groom;
  EXPECT_TRUE(sameBytes(drawn(full, 128, cam).strands, drawn(full, 128, cam).strands));
  double nearest = 1e9, farthest = 0;
  uint32_t keptNear = 0, keptFar = 0;
  for (uint32_t k = 0; k < 9; ++k) {
    const glm::vec3 c = sb::groom_rule::groomPlace(g.centre, g.placements[k]);
    const double d = glm::length(c - cam.eye);
    const double pixels =
        2.0 * g.radius * 64.0 / (d * std::tan(0.5 * cam.fovYDegrees * 3.14159265358979 / 180.0));
    const double share = std::min(1.0, (pixels / 64.0) * (pixels / 64.0));
    EXPECT_NEAR(double(g.lods[k].kept) / 96.0, share, 0.5 / 96.0 + 1e-9) << "instance " << k;
    EXPECT_EQ(g.lods[k].widen, float(96.0 / g.lods[k].kept));
    if (d < nearest) nearest = d, keptNear = g.lods[k].kept;
    if (d > farthest) farthest = d, keptFar = g.lods[k].kept;
  }
  EXPECT_LT(keptFar, keptNear);
  EXPECT_LT(keptFar, 96u);
  // Twice as far: a quarter of the share (up to rounding and the floor of one strand).
  sb::Camera back = cam;
  back.eye = cam.target + 2.0f * (cam.eye - cam.target);
  const sb::Groom& b = drawn(full, 128, back).groom;
  EXPECT_LT(b.totalStrands(), g.totalStrands());
  for (uint32_t k = 0; k < 9; ++k) EXPECT_LE(b.lods[k].kept, g.lods[k].kept);
}

// Width compensation: with --primitive world the kept strands, widened by
// strands / kept, cover what all strands covered. The hair's mean brightness over
// the black background (no shadows: each strand shaded alike on average) is its
// coverage times its mean shade: at a quarter of the strands it stays within 15%
// of the full model's (exact transparency); without the widening (lines, the
// control) it falls out of that band.
TEST(GroomLod, WideningKeepsTheMeanCoverage) {
  auto brightness = [](const std::string& lod, const std::string& primitive = "world") {
    sb::RenderRequest r;
    r.backend = "gl";
    r.scene = "straight:strands=400,points=8,seed=3,head=0,alpha=0.5,guides=8" + lod;
    r.shadow = "none";
    r.oit = "abuffer";
    r.primitive = primitive;
    r.width = r.height = 64;
    r.warmup = 0;
    const sb::RenderResult out = sb::runRender(r);
    double sum = 0;
    for (std::size_t i = 0; i < out.image.pixels.size(); i += 4)
      sum += out.image.pixels[i] + out.image.pixels[i + 1] + out.image.pixels[i + 2];
    return sum;
  };
  const double all = brightness(""), quarter = brightness(",lod=0.25");
  std::cout << "brightness: all strands " << all << ", a quarter widened 4x " << quarter
            << " (ratio " << quarter / all << ")\n";
  EXPECT_GT(all, 0.0);
  EXPECT_NEAR(quarter / all, 1.0, 0.15);
  // The control: lines take no width from the strands, so nothing compensates
  // there and the brightness falls out of the band (lines overlap more, so not to
  // a quarter).
  const double lines = brightness(",lod=0.25", "lines") / brightness("", "lines");
  std::cout << "lines (not widened): ratio " << lines << "\n";
  EXPECT_LT(lines, 0.85);
}

// The render JSON's lod: the shares kept and the image's error against the full
// model's exact reference (error.full_model), which is the reference a run
// without the level of detail makes: the same camera (fitted to the full model).
// The control: a level of detail that keeps everything gives error.image's.
TEST(GroomLod, TheErrorIsAgainstTheFullModelsReference) {
  auto run = [](const std::string& lod) {
    sb::RenderRequest r;
    r.backend = "gl";
    r.scene = std::string(kGroom) + ",guides=4,clump=0.3" + lod;
    r.shadow = "shadowmap";
    r.oit = "abuffer";
    r.primitive = "world";
    r.width = r.height = 48;
    r.warmup = 0;
    r.reference = true;
    return sb::runRender(r);
  };
  const sb::RenderResult full = run(""), quarter = run(",lod=0.25"), all = run(",lod_pixels=1");
  EXPECT_FALSE(full.measure<sb::LevelOfDetail>());
  const sb::LevelOfDetail* q = quarter.measure<sb::LevelOfDetail>();
  ASSERT_TRUE(q && q->fullModelError && quarter.imageError);
  EXPECT_EQ(q->by, "lod");
  EXPECT_EQ(q->shares, std::vector<double>{0.25});
  EXPECT_EQ(q->strandsDrawn, 24u);
  EXPECT_EQ(q->strandsFull, 96u);
  EXPECT_EQ(quarter.scene.strands, 24u);
  EXPECT_EQ(q->fullModelError->rmse, sb::compareImages(quarter.image, full.referenceImage).rmse);
  EXPECT_NE(q->fullModelError->rmse, quarter.imageError->rmse);
  const sb::LevelOfDetail* a = all.measure<sb::LevelOfDetail>();
  ASSERT_TRUE(a && a->fullModelError && all.imageError);
  EXPECT_EQ(a->shares, std::vector<double>{1.0});
  EXPECT_EQ(a->fullModelError->rmse, all.imageError->rmse);
  const nlohmann::json j = sb::renderJson(quarter);
  EXPECT_EQ(j["lod"]["share"]["mean"], 0.25) << j["lod"].dump();
  EXPECT_EQ(j["lod"]["lod"], 0.25);
  EXPECT_EQ(j["error"]["full_model"]["image"]["rmse"], q->fullModelError->rmse);
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

// With the level of detail on (lod_pixels: a share of its own per instance, so
// the kept strands' layout differs between instances), too.
TEST_P(GeometryCompute, TheDeviceMakesTheCpusStrandsBitForBit) {
  const sb::Scene full =
      scene(std::string(kGroom) + ",guides=4,clump=0.3,noise=0.5,instances=5,lod_pixels=40");
  sb::RenderRequest req = request(GetParam(), "cpu", "none", "none");
  const sb::Scene s = sb::withLevelOfDetail(full, sb::makeRenderSettings(req, full).camera, 48);
  std::vector<uint32_t> kept;
  for (const sb::GroomInstanceLod& l : s.groom.lods) kept.push_back(l.kept);
  ASSERT_LT(*std::min_element(kept.begin(), kept.end()), 96u);
  ASSERT_NE(*std::min_element(kept.begin(), kept.end()),
            *std::max_element(kept.begin(), kept.end()));
  std::vector<std::vector<uint8_t>> buffers[2];
  for (int path = 0; path < 2; ++path) {
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
