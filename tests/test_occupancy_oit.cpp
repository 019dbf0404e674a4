// Occupancy-ordered blending (--oit occupancy; Sintorn & Assarsson 2009, 3.4):
// the pure math on the CPU on extreme inputs, then rendering on both backends:
// every option renders finite images, the eye-space slab counts hold every
// visible fragment, memory is exactly the technique's targets, GL and Vulkan
// agree, and on hair of eye depth complexity >= 100 the image is closer to
// depth peeling than weighted average blending.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "gpu_test_util.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "occupancy_maps_cpu.h"
#include "render/frame/renderer.h"
#include "techniques/occupancy_oit/occupancy_oit.h"
#include "techniques/occupancy_oit/occupancy_oit_math.h"

namespace sb {
namespace {

// ---------------------------------------------------------------- CPU math --

TEST(OccupancyOitMath, TransmittanceIsFiniteAtTheExtremes) {
  using glsl::oitTransmittance;
  EXPECT_EQ(oitTransmittance(0.0f, 0.0f), 1.0f);  // pow(0, 0) = 1 cases
  EXPECT_EQ(oitTransmittance(1.0f, 0.0f), 1.0f);
  EXPECT_EQ(oitTransmittance(1.0f, 1.0f), 0.0f);
  EXPECT_EQ(oitTransmittance(1.0f, 1e-6f), 0.0f);
  EXPECT_EQ(oitTransmittance(0.0f, 5000.0f), 1.0f);
  EXPECT_EQ(oitTransmittance(0.5f, -3.0f), 1.0f);
  for (float a : {1e-7f, 1e-4f, 0.2f, 0.5f, 0.999f, 0.9999999f}) {
    for (float o : {0.5f, 1.0f, 10.0f, 1000.0f, 5000.0f, 1e6f}) {
      const float t = oitTransmittance(a, o);
      ASSERT_TRUE(std::isfinite(t)) << a << " " << o;
      EXPECT_GE(t, 0.0f);
      EXPECT_LE(t, 1.0f);
      const double exact = std::pow(1.0 - double(a), double(o));
      EXPECT_NEAR(t, exact, 1e-5 + 1e-4 * exact) << "a " << a << " o " << o;
    }
  }
  // Monotone in the order.
  EXPECT_GT(glsl::oitTransmittance(0.2f, 10.0f), glsl::oitTransmittance(0.2f, 11.0f));
}

TEST(OccupancyOitMath, CoverageIsLambda) {
  using glsl::oitCoverage;
  using glsl::oitLog2Transmittance;
  EXPECT_EQ(oitCoverage(0.0f), 0.0f);
  EXPECT_EQ(oitLog2Transmittance(0.0f), 0.0f);
  EXPECT_EQ(oitLog2Transmittance(1.0f), -200.0f);  // no -inf in the sum
  EXPECT_EQ(oitCoverage(oitLog2Transmittance(1.0f)), 1.0f);
  EXPECT_EQ(oitCoverage(-1e30f), 1.0f);
  // Lambda = 1 - (1 - a)^n, summed as n * log2(1 - a) in fp32, relative error
  // small even for one fragment of tiny alpha (no cancellation).
  for (float a : {1e-6f, 1e-3f, 0.05f, 0.2f, 0.9f}) {
    for (int n : {1, 2, 10, 132, 3000}) {
      float log2T = 0.0f;
      for (int i = 0; i < n; ++i) log2T += oitLog2Transmittance(a);
      const double exact = 1.0 - std::pow(1.0 - double(a), n);
      const float lambda = oitCoverage(log2T);
      EXPECT_NEAR(lambda, exact, 2e-6 + 2e-3 * exact) << "a " << a << " n " << n;
    }
  }
}

// The weights of orders 0..n-1 sum to Lambda (paper, 3.4): the exact orders
// need no correction, in fp32, for n in the thousands.
TEST(OccupancyOitMath, ExactOrdersSumToLambda) {
  for (float a : {1e-4f, 0.2f, 0.7f, 1.0f}) {
    for (int n : {1, 7, 132, 4000}) {
      float sum = 0.0f, log2T = 0.0f;
      for (int o = 0; o < n; ++o) {
        sum += glsl::oitWeight(a, float(o));
        log2T += glsl::oitLog2Transmittance(a);
      }
      EXPECT_NEAR(sum, glsl::oitCoverage(log2T), 1e-4f) << "a " << a << " n " << n;
    }
  }
}

TEST(OccupancyOitMath, ResolveRenormalisesToLambdaWithoutNaN) {
  using glsl::oitResolve;
  // No hair: nothing added, background kept.
  glm::vec4 r = oitResolve(glm::vec4(0.0f), 0.0f, true);
  EXPECT_EQ(r, glm::vec4(0.0f));
  // Weights sum 0.5 but Lambda 0.75 (two fragments, a = 0.5): scaled by 1.5.
  r = oitResolve(glm::vec4(0.1f, 0.2f, 0.3f, 0.5f), -2.0f, true);
  EXPECT_NEAR(r.x, 0.15f, 1e-6f);
  EXPECT_NEAR(r.z, 0.45f, 1e-6f);
  EXPECT_NEAR(r.w, 0.75f, 1e-6f);
  // Without the correction the colour is kept, the background still (1 - a)^n.
  r = oitResolve(glm::vec4(0.1f, 0.2f, 0.3f, 0.5f), -2.0f, false);
  EXPECT_NEAR(r.x, 0.1f, 1e-7f);
  EXPECT_NEAR(r.w, 0.75f, 1e-6f);
  // Weights that underflowed to zero (or a denormal) with Lambda near 1: finite.
  for (float w : {0.0f, 1e-38f, 1e-45f}) {
    r = oitResolve(glm::vec4(w, w, w, w), -200.0f, true);
    for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(r[c])) << w;
    EXPECT_LE(r.x, 1.0f);
  }
  // alpha = 0 everywhere: zero weights, zero coverage.
  r = oitResolve(glm::vec4(0.0f), glsl::oitLog2Transmittance(0.0f), true);
  EXPECT_EQ(r, glm::vec4(0.0f));
}

using PixelMaps = sbtest::OccupancyMaps;

TEST(OccupancyOitMath, OrderIsExactWithOneFragmentPerSetBit) {
  // Fragments on slice starts, the last at the far end: orders 0..n-1.
  std::vector<float> z;
  for (int k = 0; k < 5; ++k) z.push_back(0.3f + 0.1f * float(k));
  PixelMaps m(z, 128, 4);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(m.order(z[k]), float(k), 1e-3f) << k;
  // One fragment, or all at one depth: order 0 (no NaN from an empty range).
  PixelMaps one({0.5f}, 128, 4);
  EXPECT_EQ(one.order(0.5f), 0.0f);
  PixelMaps same({0.5f, 0.5f, 0.5f}, 128, 4);
  EXPECT_EQ(same.order(0.5f), 0.0f);
}

TEST(OccupancyOitMath, OrderStaysInRangeAndFollowsDepth) {
  // 3000 clustered fragments (a stray one in front): orders in [0, n-1],
  // non-decreasing with depth, ends exact, close to the true order.
  std::vector<float> z = {0.1f};
  uint32_t state = 12345u;
  for (int i = 0; i < 2999; ++i) {
    state = state * 1664525u + 1013904223u;
    const float u = float(state >> 8) / float(1u << 24);
    z.push_back(0.6f + 0.05f * u * u);
  }
  std::sort(z.begin(), z.end());
  PixelMaps m(z, 128, 4);
  float previous = -1.0f, worst = 0.0f;
  for (std::size_t k = 0; k < z.size(); ++k) {
    const float o = m.order(z[k]);
    ASSERT_TRUE(std::isfinite(o));
    EXPECT_GE(o, previous - 1e-3f);
    previous = o;
    worst = std::max(worst, std::abs(o - float(k)));
  }
  EXPECT_EQ(m.order(z.front()), 0.0f);
  EXPECT_NEAR(m.order(z.back()), float(z.size() - 1), 1e-2f);
  std::cout << "[ measured ] 3000 clustered fragments: worst order error " << worst << "\n";
  // The slab assumption (equal fragments per set bit) is off for this skewed
  // cluster; the error is bounded, not small.
  EXPECT_LT(worst, 0.3f * float(z.size()));
  // Uniformly spread fragments: the estimate is close.
  std::vector<float> u;
  for (int i = 0; i < 3000; ++i) u.push_back(0.2f + 0.5f * float(i) / 2999.0f);
  PixelMaps mu(u, 128, 4);
  float worstUniform = 0.0f;
  for (std::size_t k = 0; k < u.size(); ++k)
    worstUniform = std::max(worstUniform, std::abs(mu.order(u[k]) - float(k)));
  std::cout << "[ measured ] 3000 uniform fragments: worst order error " << worstUniform << "\n";
  EXPECT_LT(worstUniform, 0.01f * float(u.size()));
}

// -------------------------------------------------------------- rendering --

struct Rendered {
  Image image;
  DepthComplexity eye;
  std::size_t oitBytes = 0;
  std::vector<std::string> warnings, passes;
  std::vector<float> slabTotals;  // per pixel, summed over slabs
};

Rendered render(Device& dev, const std::string& sceneSpec, uint32_t size,
                const std::string& oitSpec, const std::string& shadowSpec = "none") {
  const Scene scene = makeScene(Spec::parse(sceneSpec));
  const RenderSettings s = sbtest::fittedSettings(scene, size);
  std::size_t before = 0;
  for (const auto& a : dev.allocations())
    if (a.owner == Owner::Oit) before += a.bytes;
  Renderer r(dev, scene, s, makeShadowTechnique(Spec::parse(shadowSpec)),
             makeOitTechnique(Spec::parse(oitSpec)));
  r.renderFrame();
  Rendered out;
  out.image = imageFromRows(r.readColor(), int(size), int(size), PixelType::Float32, 4);
  for (const auto& a : dev.allocations())
    if (a.owner == Owner::Oit) out.oitBytes += a.bytes;
  out.oitBytes -= before;
  if (auto c = r.oit().depthComplexity()) out.eye = *c;
  out.warnings = r.warnings();
  out.passes = r.graphPasses();
  if (auto* occ = dynamic_cast<OccupancyOit*>(&r.oit())) {
    const std::size_t pixels = std::size_t(size) * size;
    out.slabTotals.assign(pixels, 0.0f);
    // The layers one after the other, 4 slabs per texel of each.
    const std::vector<float> v = sbtest::floats(dev.readTexture(occ->slabMap()));
    for (std::size_t i = 0; i < v.size(); ++i) out.slabTotals[i / 4 % pixels] += v[i];
  }
  return out;
}

int nonFinite(const Image& im) {
  int n = 0;
  for (float v : im.pixels) n += std::isfinite(v) ? 0 : 1;
  return n;
}

class OccupancyOitTest : public sbtest::BackendTest {};

const char* kCurly = "curly:strands=300,points=24,alpha=0.4,head=0";

TEST_P(OccupancyOitTest, OptionsRenderFiniteImages) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kCurly, "occupancy"},
      {kCurly, "occupancy:slices=32,slabs=1"},
      {kCurly, "occupancy:slices=512,slabs=16"},
      {kCurly, "occupancy:slices=1024,slabs=32"},  // 8 layers of each array: the cap
      {kCurly, "occupancy:lambda=off"},
      {"curly:strands=300,points=24,alpha=1", "occupancy"},  // with the head mesh
      {"curly:strands=300,points=24,alpha=0,head=0", "occupancy"},
      {"straight:strands=400,points=10,alpha=1,head=0", "occupancy"},
  };
  for (const auto& [sceneSpec, oit] : cases) {
    SCOPED_TRACE(sceneSpec + " " + oit);
    const Rendered r = render(*dev_, sceneSpec, 64, oit);
    EXPECT_EQ(nonFinite(r.image), 0);
    EXPECT_TRUE(r.warnings.empty());
    float maxv = 0.0f;
    for (float v : r.image.pixels) maxv = std::max(maxv, v);
    EXPECT_LT(maxv, 4.0f);
  }
  EXPECT_THROW(makeOitTechnique(Spec::parse("occupancy:slices=100")), InputError);
  EXPECT_THROW(makeOitTechnique(Spec::parse("occupancy:slices=128,slabs=3")), InputError);
}

// With an occupancy shadow the accumulation binds both sets of maps.
TEST_P(OccupancyOitTest, RendersWithOccupancyShadows) {
  const Rendered r = render(*dev_, kCurly, 64, "occupancy", "occupancy:size=64");
  EXPECT_EQ(nonFinite(r.image), 0);
  const std::vector<std::string> expected = {"occupancy_oit.depth_range", "occupancy_oit.occupancy",
                                             "occupancy_oit.slabs", "occupancy_oit.accumulate",
                                             "occupancy_oit.resolve"};
  for (const auto& p : expected)
    EXPECT_NE(std::find(r.passes.begin(), r.passes.end(), p), r.passes.end()) << p;
}

// The slab counts hold every visible hair fragment: their sum over the image
// is depth peeling's fragment count, and memory is exactly the targets.
// The slab counts hold every visible hair fragment: without a mesh their sum
// over the image is depth peeling's fragment count; the head mesh hides some
// (peel's count is not used there: its storage-writing count pass has no
// early fragment tests, so it also counts hair behind the mesh). Memory is
// exactly the technique's targets.
TEST_P(OccupancyOitTest, SlabsCountEveryFragmentAndMemoryIsTheTargets) {
  const std::string withHead = "curly:strands=300,points=24,alpha=0.4";
  const Rendered peel = render(*dev_, kCurly, 64, "peel");
  for (const std::string oit :
       {"occupancy", "occupancy:slices=256,slabs=8", "occupancy:slices=1024,slabs=32"}) {
    SCOPED_TRACE(oit);
    const Rendered occ = render(*dev_, kCurly, 64, oit);
    const Rendered head = render(*dev_, withHead, 64, oit);
    double total = 0, headTotal = 0;
    for (float v : occ.slabTotals) total += v;
    for (float v : head.slabTotals) headTotal += v;
    EXPECT_EQ(uint64_t(total), peel.eye.total);
    EXPECT_GT(total, 0.0);
    EXPECT_GT(headTotal, 0.0);
    EXPECT_LT(headTotal, total);
    // RG32F range + RGBA32UI bits + RGBA32F slabs (as many layers) + RGBA32F accum + R32F.
    const std::size_t targets = oit == "occupancy"                      ? 1
                                : oit.find("1024") != std::string::npos ? 8
                                                                        : 2;
    EXPECT_EQ(occ.oitBytes, std::size_t(64) * 64 * (8 + targets * 32 + 16 + 4));
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, OccupancyOitTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// Both backends draw the same image (within 2e-3), with no validation message.
TEST(OccupancyOitBackends, GlAndVulkanAgree) {
  auto [gl, vk, unavailable] = sbtest::makeBothBackends();
  if (!unavailable.empty()) GTEST_SKIP() << unavailable;
  const std::size_t messages = validationMessageCount();
  for (const std::string& scene :
       {std::string(kCurly), std::string("curly:strands=300,points=24,alpha=0.4")}) {
    for (const std::string oit :
         {"occupancy", "occupancy:slices=64,slabs=2,lambda=off", "occupancy:slices=1024,slabs=8"}) {
      SCOPED_TRACE(scene + " " + oit);
      const Rendered a = render(*gl, scene, 64, oit);
      const Rendered b = render(*vk, scene, 64, oit);
      const ImageError e = compareImages(a.image, b.image, 2e-3);
      std::cout << "[ measured ] gl vs vulkan " << scene << " " << oit << ": max abs " << e.maxAbs
                << " rmse " << e.rmse << "\n";
      EXPECT_LT(e.maxAbs, 2e-3);
    }
  }
  EXPECT_EQ(validationMessageCount(), messages);
}

// The acceptance: eye depth complexity >= 100, RMSE against depth
// peeling lower for occupancy-ordered blending than for weighted average.
TEST_P(OccupancyOitTest, CloserToPeelingThanWeightedAverage) {
  const std::string scene = "clustered:strands=1500,points=6,head=0,alpha=0.2";
  const Rendered peel = render(*dev_, scene, 48, "peel");
  std::cout << "[ measured ] " << GetParam() << " eye depth complexity max " << peel.eye.max
            << " mean " << peel.eye.mean << "\n";
  ASSERT_GE(peel.eye.max, 100u);
  const Rendered occ = render(*dev_, scene, 48, "occupancy");
  const Rendered occNoLambda = render(*dev_, scene, 48, "occupancy:lambda=off");
  const double rmseOcc = compareImages(occ.image, peel.image).rmse;
  std::cout << "[ measured ] " << GetParam() << " rmse vs peel: occupancy " << rmseOcc
            << ", occupancy lambda=off " << compareImages(occNoLambda.image, peel.image).rmse
            << "\n";
  EXPECT_EQ(nonFinite(occ.image), 0);
  std::unique_ptr<OitTechnique> wavg;
  try {
    wavg = makeOitTechnique(Spec::parse("wavg"));
  } catch (const InputError& e) {
    GTEST_SKIP() << "weighted average blending ('wavg') is not registered yet: " << e.what();
  }
  const Rendered avg = render(*dev_, scene, 48, "wavg");
  const double rmseAvg = compareImages(avg.image, peel.image).rmse;
  std::cout << "[ measured ] " << GetParam() << " rmse vs peel: wavg " << rmseAvg << "\n";
  EXPECT_LT(rmseOcc, rmseAvg);
}

}  // namespace
}  // namespace sb
