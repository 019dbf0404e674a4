// Transparency by layers and moments: kbuffer (TressFX 4's
// k-buffer over per-pixel lists), mlab (Salvi & Vaidyanathan 2014, merged in
// primitive order in a resolve where there is no fragment-shader interlock)
// and mboit (Muenstermann et al. 2018, power moments). First their math
// headers on the CPU against an exact compositing of the same fragments, at
// alpha 0 and 1, with 1 and with thousands of layers; then rendering on both
// backends against depth peeling on hair of eye depth complexity >= 100, with
// the papers' orderings of the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <vector>

#include "gpu_test_util.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "techniques/kbuffer/kbuffer_math.h"
#include "techniques/mboit/mboit_math.h"
#include "techniques/mlab/mlab_math.h"

namespace sb {
namespace {

// ---------------------------------------------------------------- CPU math --

struct Frag {
  glm::vec4 color;  // rgb, alpha
  glm::uvec2 key;   // depth bits, primitive id
  float depth;      // in [0, 1]
};

// Fragments at random depths, in submission (primitive) order.
std::vector<Frag> randomFragments(int n, float alpha, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Frag> f;
  for (int i = 0; i < n; ++i) {
    const float d = 0.05f + 0.9f * u(rng);
    uint32_t bits = 0;
    std::memcpy(&bits, &d, 4);
    f.push_back({glm::vec4(u(rng), u(rng), u(rng), alpha), glm::uvec2(bits, uint32_t(i)), d});
  }
  return f;
}

// Exact front-to-back compositing: premultiplied (rgb, 1 - T).
glm::vec4 exactComposite(std::vector<Frag> f) {
  std::sort(f.begin(), f.end(), [](const Frag& a, const Frag& b) {
    return a.key.x < b.key.x || (a.key.x == b.key.x && a.key.y < b.key.y);
  });
  glm::vec3 c(0.0f);
  float t = 1.0f;
  for (const Frag& x : f) {
    c += t * x.color.w * glm::vec3(x.color);
    t *= 1.0f - x.color.w;
  }
  return {c, 1.0f - t};
}

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}
float maxDiff(const glm::vec4& a, const glm::vec4& b) {
  const glm::vec4 d = glm::abs(a - b);
  return std::max(std::max(d.x, d.y), std::max(d.z, d.w));
}

glm::vec4 kbuffer(const std::vector<Frag>& f, int k) {
  glsl::KBuffer kb = glsl::kbufferEmpty();
  for (const Frag& x : f) glsl::kbufferInsert(kb, k, x.color, x.key);
  return glsl::kbufferResolve(kb);
}

glm::vec4 mlab(const std::vector<Frag>& f, int layers) {
  glsl::MlabLayers m = glsl::mlabEmpty();
  for (const Frag& x : f) glsl::mlabInsert(m, layers, x.color, x.key);
  return glsl::mlabResolve(m);
}

TEST(KBufferMath, ExactWhileTheFragmentsFitAndFiniteWithThousands) {
  for (int k : {1, 2, 4, 8, 16, 32}) {
    SCOPED_TRACE(k);
    for (float alpha : {0.0f, 0.3f, 1.0f}) {
      const auto few = randomFragments(k, alpha, 7u + uint32_t(k));
      EXPECT_LT(maxDiff(kbuffer(few, k), exactComposite(few)), 1e-5f) << alpha;
      const auto many = randomFragments(5000, alpha, 11u);
      const glm::vec4 r = kbuffer(many, k);
      EXPECT_TRUE(finite(r));
      EXPECT_GE(r.w, 0.0f);
      EXPECT_LE(r.w, 1.0f);
      if (alpha == 0.0f) {
        EXPECT_EQ(r, glm::vec4(0.0f));
      }
      // Opaque fragments: the nearest one is all that shows, for every k.
      if (alpha == 1.0f) {
        EXPECT_LT(maxDiff(r, exactComposite(many)), 1e-6f);
      }
    }
    // One layer.
    const auto one = randomFragments(1, 0.5f, 3u);
    EXPECT_LT(maxDiff(kbuffer(one, k), exactComposite(one)), 1e-6f);
  }
}

// The k-buffer's error against the exact composite does not grow with k
// (averaged over pixels of 150 fragments), and a deliberately wrong resolve
// (the tail blended in front of the kept fragments) is caught as worse.
TEST(KBufferMath, ErrorDoesNotGrowWithK) {
  double previous = 1e9;
  for (int k : {1, 2, 4, 8, 16, 32}) {
    double err = 0;
    for (uint32_t seed = 0; seed < 64; ++seed) {
      const auto f = randomFragments(150, 0.25f, seed);
      err += maxDiff(kbuffer(f, k), exactComposite(f));
    }
    std::cout << "[ measured ] k-buffer k=" << k << " mean max error " << err / 64 << "\n";
    EXPECT_LE(err, previous * 1.0001);
    previous = err;
  }
  const auto f = randomFragments(150, 0.25f, 1u);
  glsl::KBuffer kb = glsl::kbufferEmpty();
  for (const Frag& x : f) glsl::kbufferInsert(kb, 8, x.color, x.key);
  glm::vec4 wrong = glm::vec4(0, 0, 0, 1);  // kept first, tail over them: the wrong order
  for (int i = 0; i < kb.size; ++i) wrong = glsl::kbufferOver(wrong, kb.color[i]);
  wrong = glsl::kbufferOver(wrong, kb.tail);
  EXPECT_GT(maxDiff(glm::vec4(glm::vec3(wrong), 1.0f - wrong.w), exactComposite(f)),
            2.0f * maxDiff(glsl::kbufferResolve(kb), exactComposite(f)));
}

TEST(MlabMath, ExactWhileTheFragmentsFitAndFiniteWithThousands) {
  for (int layers : {1, 2, 4, 8, 32}) {
    SCOPED_TRACE(layers);
    for (float alpha : {0.0f, 0.3f, 1.0f}) {
      const auto few = randomFragments(layers, alpha, 5u + uint32_t(layers));
      EXPECT_LT(maxDiff(mlab(few, layers), exactComposite(few)), 1e-5f) << alpha;
      const auto many = randomFragments(5000, alpha, 13u);
      const glm::vec4 r = mlab(many, layers);
      EXPECT_TRUE(finite(r));
      EXPECT_GE(r.w, 0.0f);
      EXPECT_LE(r.w, 1.0f + 1e-6f);
      // Coverage is exact whatever the merges: 1 - prod(1 - a).
      EXPECT_NEAR(r.w, exactComposite(many).w, 1e-4f);
      if (alpha == 0.0f) {
        EXPECT_EQ(r, glm::vec4(0.0f));
      }
      if (alpha == 1.0f) {
        EXPECT_LT(maxDiff(r, exactComposite(many)), 1e-6f);
      }
    }
  }
}

// In depth order (either way) every merge is exact "over" compositing, so
// MLAB is exact for any number of layers; in submission (random) order the
// merges approximate, and more layers approximate better on average (the
// comparison can fail: one layer really is wrong there).
TEST(MlabMath, SortedArrivalIsExactAndMoreLayersHelp) {
  auto f = randomFragments(300, 0.3f, 21u);
  const glm::vec4 exact = exactComposite(f);
  double random1 = 0, random8 = 0;
  for (uint32_t seed = 0; seed < 32; ++seed) {
    const auto g = randomFragments(300, 0.3f, 200u + seed);
    random1 += maxDiff(mlab(g, 1), exactComposite(g));
    random8 += maxDiff(mlab(g, 8), exactComposite(g));
  }
  std::sort(f.begin(), f.end(), [](const Frag& a, const Frag& b) { return a.depth < b.depth; });
  EXPECT_LT(maxDiff(mlab(f, 1), exact), 1e-5f);
  std::reverse(f.begin(), f.end());
  EXPECT_LT(maxDiff(mlab(f, 1), exact), 1e-5f);
  std::cout << "[ measured ] mlab in random order, mean max error: 1 layer " << random1 / 32
            << ", 8 layers " << random8 / 32 << "\n";
  EXPECT_GT(random1 / 32, 1e-3);
  EXPECT_LT(random8, random1);
}

// Exact transmittance in front of warped depth zf.
float exactTransmittance(const std::vector<Frag>& f, float zf) {
  double t = 1.0;
  for (const Frag& x : f)
    if (x.depth * 2.0f - 1.0f < zf) t *= 1.0 - double(x.color.w);
  return float(t);
}

struct Moments {
  float b0 = 0;
  glm::vec4 low{0.0f}, high{0.0f};
};
Moments moments(const std::vector<Frag>& f) {
  Moments m;
  for (const Frag& x : f) {
    const float a = glsl::mboitAbsorbance(x.color.w), z = x.depth * 2.0f - 1.0f;
    m.b0 += a;
    m.low += a * glsl::mboitPowersLow(z);
    m.high += a * glsl::mboitPowersHigh(z);
  }
  return m;
}

// Mean absolute transmittance error over depths, for 2n moments.
double mboitError(const std::vector<Frag>& f, int n, int bits, float biasScale = 1.0f) {
  const Moments m = moments(f);
  double err = 0;
  int count = 0;
  for (float zf = -0.99f; zf < 1.0f; zf += 0.02f, ++count) {
    const float t = glsl::mboitTransmittance(
        n, m.b0, m.low, m.high, zf, glsl::mboitBias(n, bits) * biasScale, SB_MBOIT_OVERESTIMATION);
    err += std::abs(t - exactTransmittance(f, zf));
  }
  return err / count;
}

TEST(MboitMath, FiniteAndBoundedAtTheExtremes) {
  for (int n : {2, 3, 4}) {
    for (int bits : {16, 32}) {
      SCOPED_TRACE(std::to_string(n) + " " + std::to_string(bits));
      const float bias = glsl::mboitBias(n, bits);
      // Nothing drawn: fully transmissive.
      EXPECT_EQ(
          glsl::mboitTransmittance(n, 0.0f, glm::vec4(0.0f), glm::vec4(0.0f), 0.3f, bias, 0.25f),
          1.0f);
      for (float alpha : {0.0f, 1e-4f, 0.3f, 0.999f, 1.0f}) {
        for (int count : {1, 2, 100, 5000}) {
          const auto f = randomFragments(count, alpha, uint32_t(count) + 3u);
          const Moments m = moments(f);
          EXPECT_TRUE(std::isfinite(m.b0));
          for (float zf : {-1.0f, -0.5f, 0.0f, 0.37f, 1.0f}) {
            const float t = glsl::mboitTransmittance(n, m.b0, m.low, m.high, zf, bias, 0.25f);
            ASSERT_TRUE(std::isfinite(t)) << alpha << " " << count << " " << zf;
            EXPECT_GE(t, 0.0f);
            EXPECT_LE(t, 1.0f);
            if (alpha == 0.0f) {
              EXPECT_EQ(t, 1.0f);
            }
          }
          const glm::vec4 r = glsl::mboitResolve(glm::vec4(0.5f, 0.2f, 0.1f, 0.6f), m.b0);
          EXPECT_TRUE(finite(r));
          EXPECT_NEAR(r.w, std::exp(-m.b0), 1e-6f);
        }
      }
      // One opaque fragment: all of its light in front of it, none behind.
      const auto one = randomFragments(1, 1.0f, 9u);
      const Moments m = moments(one);
      const float z = one[0].depth * 2.0f - 1.0f;
      EXPECT_GT(glsl::mboitTransmittance(n, m.b0, m.low, m.high, z - 0.2f, bias, 0.25f), 0.9f);
      EXPECT_LT(glsl::mboitTransmittance(n, m.b0, m.low, m.high, z + 0.2f, bias, 0.25f), 1e-3f);
    }
  }
  EXPECT_EQ(glsl::mboitResolve(glm::vec4(0.0f), 0.0f), glm::vec4(0, 0, 0, 1));
}

// More moments reconstruct the transmittance better, and the paper's small
// bias beats a far too large one (the error measure can fail).
TEST(MboitMath, MoreMomentsAreCloser) {
  double e4 = 0, e6 = 0, e8 = 0, eBiased = 0;
  for (uint32_t seed = 0; seed < 16; ++seed) {
    const auto f = randomFragments(8, 0.35f, 100u + seed);
    e4 += mboitError(f, 2, 32);
    e6 += mboitError(f, 3, 32);
    e8 += mboitError(f, 4, 32);
    eBiased += mboitError(f, 3, 32, 1e4f);
  }
  std::cout << "[ measured ] mboit mean |T - exact|: 4 moments " << e4 / 16 << ", 6 " << e6 / 16
            << ", 8 " << e8 / 16 << ", 6 with bias x1e4 " << eBiased / 16 << "\n";
  EXPECT_LT(e6, e4);
  EXPECT_LT(e8, e6);
  EXPECT_GT(eBiased, e6 * 1.1);
}

// -------------------------------------------------------------- rendering --

struct Rendered {
  Image image;
  DepthComplexity eye;
  std::vector<std::string> warnings;
  std::vector<Counter> counters;
  std::string emulated;
};

Rendered render(Device& dev, const std::string& sceneSpec, uint32_t size,
                const std::string& oitSpec) {
  const Scene scene = makeScene(Spec::parse(sceneSpec));
  const RenderSettings s = sbtest::fittedSettings(scene, size);
  Renderer r(dev, scene, s, makeShadowTechnique(Spec::parse("none")),
             makeOitTechnique(Spec::parse(oitSpec)));
  r.renderFrame();
  Rendered out;
  out.image = imageFromRows(r.readColor(), int(size), int(size), PixelType::Float32, 4);
  if (auto c = r.oit().depthComplexity()) out.eye = *c;
  out.warnings = r.warnings();
  out.counters = r.oit().counters(dev);
  out.emulated = r.oit().timingEmulated();
  return out;
}

uint64_t counter(const Rendered& r, const std::string& name) {
  for (const Counter& c : r.counters)
    if (c.name == name) return uint64_t(c.value);
  ADD_FAILURE() << "no counter " << name;
  return 0;
}

int nonFinite(const Image& im) {
  int n = 0;
  for (float v : im.pixels) n += std::isfinite(v) ? 0 : 1;
  return n;
}

class OitLayersTest : public sbtest::BackendTest {};

const char* kCurly = "curly:strands=300,points=24,alpha=0.4,head=0";
// Eye depth complexity >= 100 at 48x48 (tests/test_occupancy_oit.cpp).
const char* kDense = "clustered:strands=1500,points=6,head=0,alpha=0.2";

TEST_P(OitLayersTest, OptionsRenderFiniteImages) {
  for (const std::string oit :
       {"mboit:moments=4", "mboit:moments=6", "mboit:moments=8", "mboit:moments=4,precision=16",
        "mboit:moments=8,precision=16", "kbuffer:k=1", "kbuffer:k=32", "mlab:layers=1",
        "mlab:layers=32", "shortcut:k=1", "shortcut:k=16"}) {
    for (const std::string& scene :
         {std::string(kCurly), std::string("curly:strands=300,points=24,alpha=1"),
          std::string("curly:strands=200,points=16,alpha=0,head=0")}) {
      SCOPED_TRACE(oit + " " + scene);
      const Rendered r = render(*dev_, scene, 48, oit);
      EXPECT_EQ(nonFinite(r.image), 0);
      float maxv = 0.0f;
      for (float v : r.image.pixels) maxv = std::max(maxv, v);
      EXPECT_LT(maxv, 4.0f);
    }
  }
  EXPECT_THROW(makeOitTechnique(Spec::parse("mboit:moments=5")), InputError);
  EXPECT_THROW(makeOitTechnique(Spec::parse("mboit:precision=8")), InputError);
  EXPECT_THROW(makeOitTechnique(Spec::parse("kbuffer:k=0")), InputError);
  EXPECT_THROW(makeOitTechnique(Spec::parse("kbuffer:k=33")), InputError);
  EXPECT_THROW(makeOitTechnique(Spec::parse("mlab:layers=0")), InputError);
}

// A node pool smaller than the fragments drops exactly the excess, counted
// and warned about; a pool that fits drops nothing.
TEST_P(OitLayersTest, KBufferPoolOverflowIsCountedAndReported) {
  const Rendered fits = render(*dev_, kCurly, 48, "kbuffer:k=4");
  EXPECT_EQ(counter(fits, "dropped_fragments"), 0u);
  EXPECT_TRUE(fits.warnings.empty());
  ASSERT_GT(fits.eye.total, 1000u);
  const Rendered full = render(*dev_, kCurly, 48, "kbuffer:k=4,nodes=1000");
  EXPECT_EQ(counter(full, "pool_nodes"), 1000u);
  EXPECT_EQ(counter(full, "dropped_fragments"), fits.eye.total - 1000u);
  ASSERT_EQ(full.warnings.size(), 1u);
  EXPECT_NE(full.warnings[0].find("node pool overflow"), std::string::npos);
  EXPECT_EQ(nonFinite(full.image), 0);
}

// Without fragment-shader interlock (Mesa here) mlab merges in a resolve, its
// timing is marked emulated and every fragment is one emulated step.
TEST_P(OitLayersTest, MlabIsMarkedEmulated) {
  const DeviceInfo info = dev_->info();
  std::cout << "[ measured ] " << GetParam()
            << " fragment-shader interlock: " << (info.fragmentShaderInterlock ? "yes" : "no")
            << "\n";
  const Rendered r = render(*dev_, kCurly, 48, "mlab:layers=4");
  EXPECT_FALSE(r.emulated.empty());
  EXPECT_EQ(counter(r, "emulated_steps"), r.eye.total);
  EXPECT_TRUE(render(*dev_, kCurly, 48, "kbuffer").emulated.empty());
}

// The acceptance: on hair of eye depth complexity >= 100, RMSE
// against depth peeling: mboit with 6 power moments below weighted average;
// kbuffer non-increasing in k (1, 2, 4, 8, 16) and at 16 below weighted
// blended OIT; mlab with 4 layers below weighted average.
TEST_P(OitLayersTest, ErrorsOrderAsThePapersClaim) {
  const Rendered peel = render(*dev_, kDense, 48, "peel");
  std::cout << "[ measured ] " << GetParam() << " eye depth complexity max " << peel.eye.max
            << " mean " << peel.eye.mean << "\n";
  ASSERT_GE(peel.eye.max, 100u);
  const auto rmse = [&](const std::string& oit) {
    const Rendered r = render(*dev_, kDense, 48, oit);
    EXPECT_EQ(nonFinite(r.image), 0) << oit;
    const double e = compareImages(r.image, peel.image).rmse;
    std::cout << "[ measured ] " << GetParam() << " rmse vs peel " << oit << ": " << e << "\n";
    return e;
  };
  const double wavg = rmse("wavg"), wboit = rmse("wboit");
  EXPECT_LT(rmse("mboit:moments=6"), wavg);
  EXPECT_LT(rmse("mlab:layers=4"), wavg);
  double previous = 1e9, k16 = 0;
  for (int k : {1, 2, 4, 8, 16}) {
    const double e = rmse("kbuffer:k=" + std::to_string(k));
    EXPECT_LE(e, previous * (1.0 + 1e-6)) << "k=" << k;
    previous = k16 = e;
  }
  EXPECT_LT(k16, wboit);
}

INSTANTIATE_TEST_SUITE_P(Backends, OitLayersTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// Both backends draw the same image, with no validation message.
TEST(OitLayersBackends, GlAndVulkanAgree) {
  auto [gl, vk, unavailable] = sbtest::makeBothBackends();
  if (!unavailable.empty()) GTEST_SKIP() << unavailable;
  const std::size_t messages = validationMessageCount();
  for (const std::string oit :
       {"kbuffer:k=4", "kbuffer:k=4,nodes=5000", "mlab:layers=4", "shortcut", "shortcut:k=8"}) {
    SCOPED_TRACE(oit);
    const Rendered a = render(*gl, kCurly, 48, oit);
    const Rendered b = render(*vk, kCurly, 48, oit);
    const ImageError e = compareImages(a.image, b.image, 2e-3);
    std::cout << "[ measured ] gl vs vulkan " << oit << ": max abs " << e.maxAbs << " rmse "
              << e.rmse << "\n";
    EXPECT_LT(e.maxAbs, 2e-3);
  }
  EXPECT_EQ(validationMessageCount(), messages);
}

// mboit agrees on GL and Vulkan within the baselines' tolerance. It did not
// (moments=4 max abs 0.081, moments=8,precision=16 0.158) while the moment
// targets were bit for bit equal: Mesa miscompiled the reconstruction's
// loops bounded by the run-time moment count (tests/test_mboit_parity.cpp,
// MboitParity.ReconstructionIsTheSameOnGlVulkanAndCpu); with constant loop
// bounds both backends compute the same bits from the same moments.
TEST(OitLayersBackends, MboitGlAndVulkanAgree) {
  auto [gl, vk, unavailable] = sbtest::makeBothBackends();
  if (!unavailable.empty()) GTEST_SKIP() << unavailable;
  for (const std::string oit :
       {"mboit:moments=4", "mboit:moments=8,precision=16", "mboit:moments=6,kind=trig"}) {
    SCOPED_TRACE(oit);
    const ImageError e =
        compareImages(render(*gl, kCurly, 48, oit).image, render(*vk, kCurly, 48, oit).image, 2e-3);
    std::cout << "[ measured ] gl vs vulkan " << oit << ": max abs " << e.maxAbs << " rmse "
              << e.rmse << "\n";
    EXPECT_LT(e.maxAbs, 2e-3);
  }
}

}  // namespace
}  // namespace sb
