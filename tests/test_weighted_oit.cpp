// Single-pass blended transparency: weighted sum, weighted average (Bavoil &
// Myers 2008) and weighted blended OIT (McGuire & Bavoil 2013). The resolve
// math on the CPU (weighted_math.h, wboit_math.h: the same code the shaders
// compile), then every option rendered on both backends: finite, in range,
// GL and Vulkan within 2e-3, exact where there is at most one layer of opaque
// hair, and the error against depth peeling (the ground truth) printed.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

#include "gpu_test_util.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "scenes/scene.h"
#include "techniques/wboit/wboit_math.h"
#include "techniques/weighted/weighted_math.h"

namespace sb {
namespace {

using glm::vec3;
using glm::vec4;

// C = hair + T * dst, as the resolve pass blends it.
vec3 composite(vec4 r, vec3 dst) { return vec3(r) + r.w * dst; }

bool finiteIn01(vec4 v) {
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0f || v[i] > 1.0f) return false;
  return true;
}

// n layers of colour c, alpha a, accumulated as the shaders and blending do.
struct Layers {
  vec4 sum{0.0f};   // (sum a c, sum a)
  float n = 0;      // count
  vec4 wsum{0.0f};  // (sum c a w, sum a w)
  float revealage = 1.0f;
  void add(vec3 c, float a, float z, float d, int eq) {
    sum += vec4(c * a, a);
    n += 1.0f;
    const float w = glsl::wboitWeight(eq, z, d, a);
    wsum += vec4(c * a, a) * w;
    revealage *= 1.0f - a;
  }
};

TEST(WeightedOitMath, EmptyPixelLeavesTheBackground) {
  EXPECT_EQ(glsl::weightedSumResolve(vec4(0.0f)), vec4(0, 0, 0, 1));
  EXPECT_EQ(glsl::weightedAverageResolve(vec4(0.0f), 0.0f), vec4(0, 0, 0, 1));
  EXPECT_EQ(glsl::wboitResolve(vec4(0.0f), 1.0f), vec4(0, 0, 0, 1));
}

TEST(WeightedOitMath, AlphaZeroLeavesTheBackground) {
  for (int n : {1, 7, 5000}) {
    Layers l;
    for (int i = 0; i < n; ++i) l.add(vec3(0.9f, 0.4f, 0.1f), 0.0f, 3.0f + i * 1e-3f, 0.5f, 7);
    EXPECT_EQ(glsl::weightedSumResolve(l.sum), vec4(0, 0, 0, 1));
    EXPECT_EQ(glsl::weightedAverageResolve(l.sum, l.n), vec4(0, 0, 0, 1));
    EXPECT_EQ(glsl::wboitResolve(l.wsum, l.revealage), vec4(0, 0, 0, 1));
  }
}

TEST(WeightedOitMath, OneOpaqueLayerIsExact) {
  const vec3 c(0.8f, 0.3f, 0.6f), dst(0.2f, 0.9f, 0.1f);
  for (int eq : {0, 7, 8, 9, 10}) {
    Layers l;
    l.add(c, 1.0f, 4.0f, 0.3f, eq);
    for (vec4 r : {glsl::weightedSumResolve(l.sum), glsl::weightedAverageResolve(l.sum, l.n),
                   glsl::wboitResolve(l.wsum, l.revealage)}) {
      EXPECT_EQ(r.w, 0.0f);
      const vec3 out = composite(r, dst);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(out[i], c[i], 1e-6f) << "eq " << eq;
    }
  }
}

TEST(WeightedOitMath, OneLayerMatchesOver) {
  const vec3 c(0.8f, 0.3f, 0.6f), dst(0.2f, 0.9f, 0.1f);
  for (float a : {0.01f, 0.3f, 0.5f, 0.99f}) {
    Layers l;
    l.add(c, a, 4.0f, 0.3f, 10);
    const vec3 over = a * c + (1.0f - a) * dst;
    for (vec4 r : {glsl::weightedSumResolve(l.sum), glsl::weightedAverageResolve(l.sum, l.n),
                   glsl::wboitResolve(l.wsum, l.revealage)}) {
      const vec3 out = composite(r, dst);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(out[i], over[i], 1e-5f) << "alpha " << a;
    }
  }
}

// Identical layers: weighted average and weighted blended OIT are exact
// (every colour the same, coverage 1 - (1-a)^n).
TEST(WeightedOitMath, IdenticalLayersAreExactForAverageAndWboit) {
  const vec3 c(0.7f, 0.5f, 0.2f), dst(0.1f, 0.2f, 0.9f);
  for (int n : {2, 10, 100}) {
    Layers l;
    for (int i = 0; i < n; ++i) l.add(c, 0.3f, 2.0f + 0.01f * i, 0.2f + 0.001f * i, 7);
    const float t = std::pow(0.7f, float(n));
    const vec3 exact = c * (1.0f - t) + dst * t;
    for (vec4 r :
         {glsl::weightedAverageResolve(l.sum, l.n), glsl::wboitResolve(l.wsum, l.revealage)}) {
      const vec3 out = composite(r, dst);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(out[i], exact[i], 1e-4f) << n << " layers";
    }
  }
}

// 1 to 5000 layers of random colour and alpha in [0,1] (alpha 0 and 1
// included): no NaN/Inf, everything in [0,1], over any background in [0,1].
TEST(WeightedOitMath, ManyLayersStayFiniteAndInRange) {
  uint32_t seed = 12345u;
  const auto rnd = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 24);
  };
  for (int n : {1, 2, 10, 100, 1000, 5000}) {
    for (int eq : {0, 7, 8, 9, 10}) {
      for (float fixedAlpha : {-1.0f, 0.0f, 1.0f}) {
        Layers l;
        for (int i = 0; i < n; ++i) {
          const float a = fixedAlpha >= 0.0f ? fixedAlpha : rnd();
          l.add(vec3(rnd(), rnd(), rnd()), a, 0.1f + 500.0f * rnd(), rnd(), eq);
        }
        const vec3 dst(rnd(), rnd(), rnd());
        for (vec4 r : {glsl::weightedSumResolve(l.sum), glsl::weightedAverageResolve(l.sum, l.n),
                       glsl::wboitResolve(l.wsum, l.revealage)}) {
          ASSERT_TRUE(finiteIn01(r)) << n << " layers, eq " << eq << ", alpha " << fixedAlpha;
          const vec3 out = composite(r, dst);
          for (int i = 0; i < 3; ++i) {
            EXPECT_TRUE(std::isfinite(out[i]));
            EXPECT_GE(out[i], 0.0f);
            EXPECT_LE(out[i], 1.0f + 1e-6f);
          }
        }
      }
    }
  }
}

// A 16-bit accumulation that overflowed to +inf resolves without NaN.
TEST(WeightedOitMath, OverflowToInfinityIsSuppressed) {
  const float inf = std::numeric_limits<float>::infinity();
  for (vec4 acc : {vec4(inf), vec4(inf, 1.0f, inf, inf), vec4(1.0f, 2.0f, 3.0f, inf)}) {
    const vec4 r = glsl::wboitResolve(acc, 0.0f);
    EXPECT_TRUE(finiteIn01(r));
  }
  EXPECT_EQ(glsl::wboitResolve(vec4(inf), 0.0f), vec4(1, 1, 1, 0));
}

TEST(WeightedOitMath, WeightsArePositiveAndFallWithDepth) {
  for (int eq : {7, 8, 9, 10}) {
    float prev = std::numeric_limits<float>::infinity();
    for (float t = 0.0f; t <= 1.0f; t += 0.05f) {
      const float w = glsl::wboitWeight(eq, 0.1f + 499.9f * t, t, 0.5f);
      EXPECT_GT(w, 0.0f);
      EXPECT_TRUE(std::isfinite(w));
      EXPECT_LE(w, prev) << "eq " << eq;
      prev = w;
    }
  }
  EXPECT_FLOAT_EQ(glsl::wboitWeight(0, 3.0f, 0.5f, 0.5f), 1.0f);
  // eq10 at d = 0: a * 3e3; eq 7 near the eye: clamped to a * 3e3.
  EXPECT_FLOAT_EQ(glsl::wboitWeight(10, 1.0f, 0.0f, 0.5f), 1500.0f);
  EXPECT_FLOAT_EQ(glsl::wboitWeight(7, 0.001f, 0.0f, 0.5f), 1500.0f);
}

// ---------------------------------------------------------------- GPU

const std::vector<std::string> kSpecs = {
    "wsum",
    "wavg",
    "wboit",
    "wboit:weight=const",
    "wboit:weight=eq7",
    "wboit:weight=eq8",
    "wboit:weight=eq9",
    "wboit:weight=eq10,precision=16",
    "wboit:weight=eq7,precision=16",
    "wboit:weight=const,precision=16",
};

const std::vector<std::string> kScenes = {
    "straight:strands=400,points=10,alpha=0.5,shadow_alpha=0.3",  // head: opaque mesh
    "curly:strands=300,points=24,alpha=0.4,head=0",               // no mesh: cleared
    "clustered:strands=1500,points=6,head=0,alpha=0.2",           // depth complexity ~100
};

struct Result {
  Image image;
  std::size_t oitBytes = 0;
};

Result render(Device& dev, const std::string& sceneSpec, const std::string& oit,
              const std::string& shadow = "none", uint32_t size = 64) {
  const Scene scene = makeScene(Spec::parse(sceneSpec));
  const RenderSettings s = sbtest::fittedSettings(scene, size);
  // The device keeps earlier renderers' resources: count what this one adds.
  const auto oitBytes = [&dev] {
    std::size_t n = 0;
    for (const ResourceBytes& b : dev.allocations())
      if (b.owner == Owner::Oit) n += b.bytes;
    return n;
  };
  const std::size_t before = oitBytes();
  Renderer r(dev, scene, s, makeShadowTechnique(Spec::parse(shadow)),
             makeOitTechnique(Spec::parse(oit)));
  r.renderFrame();
  Result out;
  out.image = imageFromRows(r.readColor(), int(size), int(size), PixelType::Float32, 4);
  out.oitBytes = oitBytes() - before;
  EXPECT_TRUE(r.warnings().empty());
  return out;
}

void expectFiniteIn01(const Image& im, const std::string& what) {
  std::size_t bad = 0;
  for (float v : im.pixels)
    if (!std::isfinite(v) || v < -1e-6f || v > 1.0f + 1e-5f) ++bad;
  EXPECT_EQ(bad, 0u) << what;
}

class WeightedOitTest : public sbtest::BackendTest {};

TEST_P(WeightedOitTest, EveryOptionRendersAndIsComparedWithPeeling) {
  for (const std::string& sceneSpec : kScenes) {
    const Result peel = render(*dev_, sceneSpec, "peel");
    for (const std::string& spec : kSpecs) {
      SCOPED_TRACE(sceneSpec + " " + spec);
      const Result r = render(*dev_, sceneSpec, spec);
      expectFiniteIn01(r.image, spec);
      const ImageError e = compareImages(peel.image, r.image, 1e-3, 3);
      EXPECT_EQ(e.nanPixels, 0);
      EXPECT_TRUE(std::isfinite(e.rmse));
      std::cout << "[ measured ] " << GetParam() << " " << sceneSpec << " " << spec
                << ": RMSE vs peel " << e.rmse << ", max abs " << e.maxAbs << ", oit bytes "
                << r.oitBytes << "\n";
      // Exactly the technique's targets: 16 bytes accum + 4 bytes count/revealage.
      const std::size_t px = 64 * 64;
      const std::size_t expected = spec == "wsum"                                   ? 16 * px
                                   : spec.find("precision=16") != std::string::npos ? 12 * px
                                                                                    : 20 * px;
      EXPECT_EQ(r.oitBytes, expected);
    }
  }
}

// Alpha 0: the hair vanishes (the opaque image without hair); alpha 1 with one
// strand: where one layer covers a pixel the result is the opaque hair's.
TEST_P(WeightedOitTest, AlphaLimitsMatchPeeling) {
  for (const char* spec : {"wsum", "wavg", "wboit", "wboit:weight=eq7,precision=16"}) {
    SCOPED_TRACE(spec);
    {
      const std::string sc = "straight:strands=200,points=10,alpha=0";
      const ImageError e =
          compareImages(render(*dev_, sc, "peel").image, render(*dev_, sc, spec).image, 1e-5, 3);
      EXPECT_LE(e.maxAbs, 1e-5);
    }
    const std::string sc = "straight:strands=1,points=12,alpha=1,head=0";
    const Image peel = render(*dev_, sc, "peel").image;
    const Image none = render(*dev_, sc, "none").image;
    const Image r = render(*dev_, sc, spec).image;
    // A 16-bit accumulation rounds c w and w (relative 2^-11 each).
    const float tol = std::string(spec).find("precision=16") != std::string::npos ? 2e-3f : 1e-4f;
    int hair = 0, same = 0;
    for (std::size_t p = 0; p < peel.pixels.size(); p += 4) {
      bool isHair = false, equal = true;
      for (int c = 0; c < 3; ++c) {
        isHair = isHair || peel.pixels[p + c] != 0.0f;
        equal = equal && std::abs(peel.pixels[p + c] - r.pixels[p + c]) < tol &&
                std::abs(none.pixels[p + c] - r.pixels[p + c]) < tol;
      }
      hair += isHair;
      same += isHair && equal;
    }
    std::cout << "[ measured ] " << GetParam() << " " << spec << " alpha=1, one strand: " << same
              << " of " << hair << " hair pixels equal to peel and opaque\n";
    EXPECT_GT(hair, 10);
    EXPECT_GE(same, hair * 9 / 10);
  }
}

// With a shadow technique that samples textures in the hair pass.
TEST_P(WeightedOitTest, RendersWithShadowMaps) {
  for (const char* spec : {"wsum", "wavg", "wboit"}) {
    const Result r = render(*dev_, kScenes[0], spec, "shadowmap:size=128");
    expectFiniteIn01(r.image, spec);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, WeightedOitTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// GL and Vulkan render the same images (max abs < 2e-3), with no validation messages.
TEST(WeightedOitBackends, GlAndVulkanAgree) {
  auto [gl, vk, unavailable] = sbtest::makeBothBackends();
  if (!unavailable.empty()) GTEST_SKIP() << unavailable;
  const std::size_t messages = validationMessageCount();
  for (const std::string& sceneSpec : kScenes) {
    for (const std::string& spec : kSpecs) {
      SCOPED_TRACE(sceneSpec + " " + spec);
      const ImageError e = compareImages(render(*gl, sceneSpec, spec).image,
                                         render(*vk, sceneSpec, spec).image, 2e-3, 3);
      std::cout << "[ measured ] " << sceneSpec << " " << spec << ": GL vs Vulkan max abs "
                << e.maxAbs << ", RMSE " << e.rmse << "\n";
      EXPECT_LT(e.maxAbs, 2e-3);
      EXPECT_EQ(e.nanPixels, 0);
    }
  }
  EXPECT_EQ(validationMessageCount(), messages) << "Vulkan validation messages";
}

}  // namespace
}  // namespace sb
