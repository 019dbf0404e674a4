// Opacity shadow maps and deep opacity maps: the shared reconstruction math on
// the CPU (opacity.h) on hand-made fragment lists, and both techniques on the
// GPU through the Renderer on GL and Vulkan: every option renders, the APIs
// agree, memory is exactly the maps, and error against exact shadows falls as
// maps/layers grow.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <numeric>

#include "gpu_test_util.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "scenes/view.h"
#include "techniques/dom/layers.h"
#include "techniques/osm/slicing.h"

namespace sb {
namespace {

using sbtest::floats;
using sbtest::makeDevice;

// ---- CPU: the maps a technique would build from one texel's fragments ----

// OSM maps 1..n from fragment depths: map i counts fragments with z < D_i.
std::vector<float> osmMaps(const std::vector<float>& frags, const std::vector<float>& slices) {
  std::vector<float> maps(slices.size() - 1, 0.0f);
  for (float z : frags)
    for (std::size_t i = 1; i < slices.size(); ++i)
      if (z < slices[i]) maps[i - 1] += 1.0f;
  return maps;
}

float osmVisibility(float z, const std::vector<float>& slices, const std::vector<float>& maps,
                    float alpha) {
  glsl::layerBoundsCpu = slices.data();
  glsl::layerMapsCpu = maps.data();
  return glsl::opacityVisibility(glsl::osmOpacity(z, int(maps.size())), alpha);
}

struct DomTexel {
  float z0 = 1.0f;
  std::vector<float> layers;
};

DomTexel domBuild(const std::vector<float>& frags, const std::vector<float>& d, int beyond,
                  int bits = 32) {
  DomTexel t;
  const int K = int(d.size()) - 1;
  t.layers.assign(std::size_t(K), 0.0f);
  for (float z : frags) t.z0 = std::min(t.z0, glsl::domQuantize(z, bits));
  glsl::layerBoundsCpu = d.data();
  for (float z : frags)
    for (int k = 1; k <= K; ++k)
      t.layers[std::size_t(k - 1)] += glsl::domContribution(std::max(z - t.z0, 0.0f), k, K, beyond);
  return t;
}

float domVisibility(float z, const DomTexel& t, const std::vector<float>& d, float alpha) {
  glsl::layerBoundsCpu = d.data();
  glsl::layerMapsCpu = t.layers.data();
  return glsl::opacityVisibility(glsl::domOpacity(z, t.z0, int(d.size()) - 1), alpha);
}

std::vector<std::vector<float>> fragmentLists() {
  std::vector<float> many(3000);
  for (std::size_t i = 0; i < many.size(); ++i) many[i] = 0.2f + 0.6f * float(i) / 3000.0f;
  return {{}, {0.5f}, std::vector<float>(500, 0.4f), {0.1f, 0.95f, 0.99f, 1.0f}, many};
}

// Visibility is finite, in [0,1] and non-increasing along the light ray.
void expectSane(const std::function<float(float)>& v, const std::string& what) {
  float prev = 1.0f;
  for (int i = 0; i <= 400; ++i) {
    const float z = -0.1f + 1.3f * float(i) / 400.0f;
    const float x = v(z);
    ASSERT_TRUE(std::isfinite(x)) << what << " z=" << z;
    ASSERT_GE(x, 0.0f) << what;
    ASSERT_LE(x, 1.0f) << what;
    ASSERT_LE(x, prev + 1e-6f) << what << " z=" << z;
    prev = x;
  }
}

TEST(OpacityMath, VisibilityDefinition) {
  EXPECT_EQ(glsl::opacityVisibility(0.0f, 1.0f), 1.0f);  // pow(0,0) guarded
  EXPECT_EQ(glsl::opacityVisibility(0.0f, 0.5f), 1.0f);
  EXPECT_EQ(glsl::opacityVisibility(3.0f, 1.0f), 0.0f);
  EXPECT_EQ(glsl::opacityVisibility(1e6f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(glsl::opacityVisibility(3.0f, 0.5f), 0.125f);
  EXPECT_EQ(glsl::opacityVisibility(NAN, 0.5f), 1.0f);
  EXPECT_EQ(glsl::opacityVisibility(5000.0f, 0.3f), 0.0f);
  // kappa form: exp(-kappa * n * w) with w = -ln(1-a)/kappa is the same.
  const float kappa = 8.0f * std::log(2.0f), a = 0.3f, w = -std::log(1.0f - a) / kappa;
  EXPECT_NEAR(std::exp(-kappa * 7.0f * w), glsl::opacityVisibility(7.0f, a), 1e-6f);
}

TEST(OpacityMath, OsmOnFragmentLists) {
  for (int mode : {glsl::kOsmUniform, glsl::kOsmDensity, glsl::kOsmGamma})
    for (int n : {1, 4, 16, 256})
      for (const auto& frags : fragmentLists())
        for (float alpha : {0.0f, 0.3f, 1.0f}) {
          std::vector<float> z = frags.empty() ? std::vector<float>{0.3f, 0.7f} : frags;
          const auto slices = osmSlices(n, mode, 2.0f, z);
          ASSERT_EQ(slices.size(), std::size_t(n) + 1);
          for (std::size_t i = 1; i < slices.size(); ++i) ASSERT_GE(slices[i], slices[i - 1]);
          const auto maps = osmMaps(frags, slices);
          const std::string what = "osm mode " + std::to_string(mode) + " n " + std::to_string(n) +
                                   " frags " + std::to_string(frags.size());
          expectSane([&](float x) { return osmVisibility(x, slices, maps, alpha); }, what);
          // Behind every fragment: exactly (1-a)^count; in front of all: 1.
          EXPECT_NEAR(osmVisibility(1.1f, slices, maps, alpha),
                      glsl::opacityVisibility(float(frags.size()), alpha), 1e-6f)
              << what;
          EXPECT_EQ(osmVisibility(-0.05f, slices, maps, alpha), 1.0f) << what;
        }
  // At slice depths the maps are exact.
  const std::vector<float> frags = {0.1f, 0.2f, 0.3f, 0.6f};
  const auto slices = osmSlices(4, glsl::kOsmUniform, 1.0f, frags);
  const auto maps = osmMaps(frags, slices);
  EXPECT_FLOAT_EQ(osmVisibility(slices[2], slices, maps, 0.5f), 0.125f);  // 0.1,0.2,0.3 < 0.35
}

TEST(OpacityMath, DomLayerBoundaries) {
  const std::vector<float> none;
  auto d = domBoundaries(4, glsl::kDomConstant, 0.1f, none, glsl::kDomLast, 1.0f);
  EXPECT_NEAR(d[4], 0.4f, 1e-6f);
  d = domBoundaries(4, glsl::kDomLinear, 0.1f, none, glsl::kDomLast, 1.0f);
  EXPECT_NEAR(d[4], 1.0f, 1e-6f);  // 1+2+3+4
  d = domBoundaries(4, glsl::kDomPow2, 0.1f, none, glsl::kDomLast, 1.0f);
  EXPECT_NEAR(d[4], 1.5f, 1e-6f);  // 1+2+4+8
  d = domBoundaries(5, glsl::kDomFibonacci, 0.1f, none, glsl::kDomLast, 1.0f);
  EXPECT_NEAR(d[5], 1.2f, 1e-6f);  // 1+1+2+3+5
  d = domBoundaries(3, glsl::kDomLinear, 0.1f, {2.0f, 0.5f, 1.0f}, glsl::kDomLast, 1.0f);
  EXPECT_NEAR(d[3], 0.35f, 1e-6f);
  d = domBoundaries(3, glsl::kDomConstant, 0.01f, none, glsl::kDomExtend, 0.5f);
  EXPECT_GT(d[3], 0.5f);
  d = domBoundaries(3, glsl::kDomConstant, 0.0f, none, glsl::kDomLast, 0.0f);  // empty range
  EXPECT_GT(d[1], 0.0f);
}

TEST(OpacityMath, DomCountingYukselAgainstTheThesis) {
  // Three constant layers of 0.1 behind z0: d = 0, 0.1, 0.2, 0.3. Fragments at dz = 0 (layer
  // 1), 0.15 (layer 2), 0.25 (layer 3) and 0.5 (beyond). Yuksel & Keyser: a fragment counts in
  // its own layer and every later one: layer 1 = 1, layer 2 = 2, layer 3 = 3, plus the one
  // beyond in layer 3 with beyond=last (4). The thesis (Listing 3): its own and every
  // preceding one: layer 1 = 3 (the three inside), layer 2 = 2, layer 3 = 1; beyond=last
  // counts the fourth in all three (4, 3, 2), beyond=ignore drops it.
  const std::vector<float> d = {0.0f, 0.1f, 0.2f, 0.3f};
  glsl::layerBoundsCpu = d.data();
  const std::vector<float> dz = {0.0f, 0.15f, 0.25f, 0.5f};
  auto layers = [&](bool thesis, int beyond) {
    std::vector<float> l(3, 0.0f);
    for (float z : dz)
      for (int k = 1; k <= 3; ++k)
        l[std::size_t(k - 1)] += thesis ? glsl::domContributionPreceding(z, k, 3, beyond)
                                        : glsl::domContribution(z, k, 3, beyond);
    return l;
  };
  EXPECT_EQ(layers(false, glsl::kDomLast), (std::vector<float>{1, 2, 4}));
  EXPECT_EQ(layers(false, glsl::kDomIgnore), (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(layers(true, glsl::kDomLast), (std::vector<float>{4, 3, 2}));
  EXPECT_EQ(layers(true, glsl::kDomIgnore), (std::vector<float>{3, 2, 1}));
  EXPECT_EQ(glsl::domContributionPreceding(0.05f, 0, 3, glsl::kDomLast), 0.0f);  // no layer 0
  EXPECT_EQ(glsl::domContributionPreceding(0.05f, 4, 3, glsl::kDomLast), 0.0f);
}

TEST(OpacityMath, DomOnFragmentLists) {
  const std::vector<float> none;
  for (int spacing : {glsl::kDomConstant, glsl::kDomLinear, glsl::kDomPow2, glsl::kDomFibonacci})
    for (int beyond : {glsl::kDomIgnore, glsl::kDomLast, glsl::kDomExtend})
      for (int K : {1, 3, 7, 23})
        for (int bits : {8, 16, 32})
          for (const auto& frags : fragmentLists())
            for (float alpha : {0.0f, 0.5f, 1.0f}) {
              // The range plus one step of z0's quantization, as the technique does.
              const float quantum = bits < 32 ? 1.0f / (std::exp2(float(bits)) - 1.0f) : 0.0f;
              const auto d = domBoundaries(K, spacing, 0.02f, none, beyond, 0.9f + quantum);
              const DomTexel t = domBuild(frags, d, beyond, bits);
              const std::string what = "dom spacing " + std::to_string(spacing) + " beyond " +
                                       std::to_string(beyond) + " K " + std::to_string(K) +
                                       " frags " + std::to_string(frags.size());
              expectSane([&](float z) { return domVisibility(z, t, d, alpha); }, what);
              EXPECT_EQ(domVisibility(t.z0 - 0.01f, t, d, alpha), 1.0f) << what;
              // Behind every fragment: all fragments counted unless ignored.
              const float all = glsl::opacityVisibility(float(frags.size()), alpha);
              if (beyond != glsl::kDomIgnore) {
                EXPECT_NEAR(domVisibility(1.5f, t, d, alpha), all, 1e-6f) << what;
              } else {
                EXPECT_GE(domVisibility(1.5f, t, d, alpha), all) << what;
              }
            }
  // One layer ignoring fragments beyond it: the far fragments cast nothing.
  const auto d = domBoundaries(1, glsl::kDomConstant, 0.1f, none, glsl::kDomIgnore, 1.0f);
  const DomTexel t = domBuild({0.2f, 0.25f, 0.8f, 0.9f}, d, glsl::kDomIgnore);
  EXPECT_FLOAT_EQ(domVisibility(1.0f, t, d, 0.5f), 0.25f);
  EXPECT_EQ(glsl::domQuantize(0.5f, 8), std::floor(0.5f * 255.0f) / 255.0f);
}

// ---- GPU: both techniques through the Renderer on GL and Vulkan ----

const char* kScene = "curly:strands=300,points=16,alpha=0.5,shadow_alpha=0.3";

struct Result {
  std::vector<float> color, visibility;
  std::size_t shadowBytes = 0;
};

std::size_t shadowBytes(Device& dev) {
  std::size_t n = 0;
  for (const auto& a : dev.allocations())
    if (a.owner == Owner::Shadow) n += a.bytes;
  return n;
}

// Shadow memory is the growth of owner "shadow" while the renderer lives
// (earlier renderers' resources may still be held by the device).
Result render(Device& dev, const std::string& sceneSpec, const std::string& shadow,
              uint32_t size = 64) {
  const Scene scene = makeScene(Spec::parse(sceneSpec));
  const std::size_t before = shadowBytes(dev);
  Renderer r(dev, scene, sbtest::fittedSettings(scene, size),
             makeShadowTechnique(Spec::parse(shadow)), makeOitTechnique(Spec::parse("none")),
             {Output::Color, Output::Visibility});
  r.renderFrame();
  Result out;
  out.shadowBytes = shadowBytes(dev) - before;
  out.color = floats(r.readColor());
  out.visibility = floats(r.readVisibility());
  return out;
}

const std::vector<std::string>& allOptionSpecs() {
  static const std::vector<std::string> specs = {
      "osm:size=64",
      "osm:size=64,maps=1",
      "osm:size=64,maps=7,passes=single",
      "osm:size=64,maps=29,passes=multi",
      "osm:size=64,slicing=density",
      "osm:size=64,slicing=gamma,gamma=3",
      "osm:size=64,bits=8",
      "osm:size=64,bits=8,kappa=3",
      "osm:size=64,bits=16",
      "osm:size=64,bias=0",
      "dom:size=64",
      "dom:size=64,layers=1",
      "dom:size=64,layers=7,spacing=constant",
      "dom:size=64,layers=23,spacing=pow2",
      // The cap: 8 layers of one array, each a colour attachment of the opacity pass.
      "dom:size=64,layers=31",
      "dom:size=64,layers=31,spacing=linear,size_frac=0.01,beyond=extend",
      "dom:size=64,layers=26,depth_bits=16",
      "dom:size=64,spacing=fibonacci",
      "dom:size=64,spacing=list,list=1;0.5;4",
      "dom:size=64,size_abs=0.01",
      "dom:size=64,size_frac=0.02,beyond=ignore",
      "dom:size=64,beyond=extend",
      "dom:size=64,depth_bits=8",
      "dom:size=64,depth_bits=16",
  };
  return specs;
}

class OsmDomTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* b : {"gl", "vulkan"}) {
      try {
        devices_.emplace_back(b, makeDevice(b));
      } catch (const DeviceError& e) {
        std::cout << "[ skipped  ] backend " << b << " unavailable: " << e.what() << "\n";
      }
    }
    if (devices_.empty()) GTEST_SKIP() << "no backend";
    messages_ = validationMessageCount();
  }
  void TearDown() override {
    if (!devices_.empty()) {
      EXPECT_EQ(validationMessageCount(), messages_) << "Vulkan validation";
    }
  }
  std::vector<std::pair<std::string, std::unique_ptr<Device>>> devices_;
  std::size_t messages_ = 0;
};

TEST_F(OsmDomTest, EveryOptionRendersAndTheApisAgree) {
  double worst = 0;
  for (const auto& spec : allOptionSpecs()) {
    SCOPED_TRACE(spec);
    std::vector<Result> results;
    for (auto& [name, dev] : devices_) {
      for (const std::string& scene : {std::string(kScene), std::string(kScene) + ",head=0"}) {
        Result r = render(*dev, scene, spec);
        for (float x : r.color) {
          ASSERT_TRUE(std::isfinite(x)) << name;
        }
        for (float x : r.visibility) {
          ASSERT_TRUE(std::isfinite(x)) << name;
          ASSERT_LE(x, 1.0f) << name;
          ASSERT_TRUE(x >= 0.0f || x == -1.0f) << name << ": " << x;  // -1: background
        }
        if (scene == kScene) results.push_back(std::move(r));
      }
    }
    if (results.size() == 2) {
      double maxAbs = 0;
      for (std::size_t i = 0; i < results[0].color.size(); ++i)
        maxAbs = std::max(maxAbs, double(std::abs(results[0].color[i] - results[1].color[i])));
      for (std::size_t i = 0; i < results[0].visibility.size(); ++i)
        maxAbs =
            std::max(maxAbs, double(std::abs(results[0].visibility[i] - results[1].visibility[i])));
      EXPECT_LT(maxAbs, 2e-3);
      worst = std::max(worst, maxAbs);
    }
  }
  std::cout << "[ measured ] GL vs Vulkan, max abs difference over all options: " << worst << "\n";
}

TEST_F(OsmDomTest, ShadowMemoryIsExactlyTheMaps) {
  Device& dev = *devices_.front().second;
  const std::string scene = std::string(kScene) + ",head=0";
  const Result osm = render(dev, scene, "osm:maps=128,size=512,bits=32", 16);
  EXPECT_EQ(osm.shadowBytes, std::size_t(32) * 512 * 512 * 16);
  EXPECT_EQ(osm.shadowBytes, std::size_t(128) << 20);
  const Result dom = render(dev, scene, "dom:layers=3,size=512", 16);
  EXPECT_EQ(dom.shadowBytes, std::size_t(512) * 512 * (4 + 16));
  // 31 layers: the R32F depth map and an array of 8 RGBA32F layers (paper: 34 MB
  // for 32 slices).
  const Result dom31 = render(dev, scene, "dom:layers=31,size=512", 16);
  EXPECT_EQ(dom31.shadowBytes, std::size_t(512) * 512 * (4 + 8 * 16));
  std::cout << "[ measured ] shadow_bytes osm maps=128 size=512 fp32: " << osm.shadowBytes
            << ", dom layers=3 size=512: " << dom.shadowBytes << "\n";
}

TEST_F(OsmDomTest, ErrorFallsAsMapsAndLayersGrow) {
  for (auto& [name, dev] : devices_) {
    const std::string scene = std::string(kScene) + ",head=0";
    const Result exact = render(*dev, scene, "exact:size=64");
    std::vector<double> osm, dom;
    for (int maps : {2, 8, 64})
      osm.push_back(compareVisibility(
                        render(*dev, scene, "osm:size=64,maps=" + std::to_string(maps)).visibility,
                        exact.visibility)
                        .rmse);
    for (int layers : {1, 3, 11})
      dom.push_back(compareVisibility(render(*dev, scene,
                                             "dom:size=64,spacing=constant,size_frac=0.02,layers=" +
                                                 std::to_string(layers))
                                          .visibility,
                                      exact.visibility)
                        .rmse);
    std::cout << "[ measured ] " << name << " visibility rmse vs exact: osm maps 2/8/64 " << osm[0]
              << " " << osm[1] << " " << osm[2] << "; dom layers 1/3/11 " << dom[0] << " " << dom[1]
              << " " << dom[2] << "\n";
    EXPECT_GT(osm[0], osm[1]);
    EXPECT_GT(osm[1], osm[2]);
    EXPECT_GT(dom[0], dom[1]);
    EXPECT_GT(dom[1], dom[2]);
  }
}

}  // namespace
}  // namespace sb
