// Occupancy maps (Sintorn & Assarsson 2009) and density clustering (Mertens et
// al. 2004): the reconstruction math on the CPU on hand-made fragment lists
// (empty texel, one fragment, zero depth range, fragments at the range's ends,
// thousands of fragments, alpha_s 0 and 1), then both techniques on both
// backends: every option renders without NaN and without validation messages,
// GL and Vulkan agree, occupancy maps take exactly 10 MiB at 512x512, and
// occupancy is closer to the exact visibility than a hard shadow map.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>

#include "base/options.h"
#include "gpu_test_util.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "scenes/view.h"
#include "techniques/dc/dc_math.h"
#include "techniques/occupancy/occupancy_math.h"

namespace sb {
namespace {

using sbtest::floats;

// ---------------------------------------------------------------- CPU: occupancy

// A texel's maps built from its fragment depths the way the GPU passes do.
struct OccTexel {
  float zMin = 2.0f, zMax = -2.0f;  // the cleared depth-range map: empty
  uint32_t bits[SB_OCC_MAX_WORDS] = {};
  float slabs[SB_OCC_MAX_SLABS] = {};
  int slices = 128, slabCount = 4;
};

OccTexel buildOcc(const std::vector<float>& z, int slices = 128, int slabs = 4) {
  OccTexel t;
  t.slices = slices;
  t.slabCount = slabs;
  for (float d : z) t.zMin = std::min(t.zMin, d), t.zMax = std::max(t.zMax, d);
  for (float d : z) {
    const int s = glsl::occupancySlice(d, t.zMin, t.zMax, slices);
    t.bits[s / 32] |= 1u << (s % 32);
    t.slabs[s / (slices / slabs)] += 1.0f;
  }
  return t;
}

float occCount(OccTexel& t, float z, bool useSlabs = true) {
  return glsl::occupancyCount(z, t.zMin, t.zMax, t.bits, t.slabs, t.slices, t.slabCount, useSlabs);
}

float exactCount(const std::vector<float>& z, float at) {
  return float(std::count_if(z.begin(), z.end(), [at](float d) { return d < at; }));
}

// Sweeps depth over [-0.1, 1.1]: visibility finite, in [0,1], never increasing.
template <typename CountFn>
void expectWellBehaved(CountFn count, float alpha, float maxCount) {
  float previous = 1.0f;
  for (int i = 0; i <= 2400; ++i) {
    const float z = -0.1f + 1.2f * float(i) / 2400.0f;
    const float n = count(z);
    ASSERT_TRUE(std::isfinite(n)) << "z " << z;
    EXPECT_GE(n, 0.0f) << "z " << z;
    EXPECT_LE(n, maxCount * (1.0f + 1e-5f)) << "z " << z;
    const float v = glsl::occupancyVisibility(n, alpha);
    const float w = glsl::dcVisibility(n, alpha);
    ASSERT_TRUE(std::isfinite(v) && std::isfinite(w)) << "z " << z;
    EXPECT_EQ(v, w);
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
    EXPECT_LE(v, previous + 1e-6f) << "visibility increases at z " << z;
    previous = v;
  }
}

TEST(OccupancyMath, EmptyTexelIsLit) {
  OccTexel t = buildOcc({});
  for (float z : {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f}) {
    EXPECT_EQ(occCount(t, z), 0.0f);
    EXPECT_EQ(occCount(t, z, false), 0.0f);
  }
  expectWellBehaved([&](float z) { return occCount(t, z); }, 0.5f, 0.0f);
}

TEST(OccupancyMath, OneFragment) {
  OccTexel t = buildOcc({0.4f});
  EXPECT_EQ(occCount(t, 0.3f), 0.0f);
  EXPECT_EQ(occCount(t, 0.4f), 0.0f);  // not in front of itself
  EXPECT_EQ(occCount(t, 0.41f), 1.0f);
  EXPECT_EQ(occCount(t, 0.41f, false), 1.0f);
  for (float alpha : {0.0f, 0.3f, 1.0f})
    expectWellBehaved([&](float z) { return occCount(t, z); }, alpha, 1.0f);
}

TEST(OccupancyMath, ZeroDepthRange) {
  const std::vector<float> z(3000, 0.7f);
  OccTexel t = buildOcc(z);
  EXPECT_EQ(t.slabs[0], 3000.0f);
  EXPECT_EQ(occCount(t, 0.7f), 0.0f);
  EXPECT_EQ(occCount(t, 0.7001f), 3000.0f);
  EXPECT_EQ(occCount(t, 0.7001f, false), 1.0f);  // one set bit: one fragment
  for (float alpha : {0.0f, 0.5f, 1.0f})
    expectWellBehaved([&](float d) { return occCount(t, d); }, alpha, 3000.0f);
  EXPECT_EQ(glsl::occupancyVisibility(3000.0f, 0.5f), 0.0f);  // underflows to 0, no NaN
}

TEST(OccupancyMath, FragmentsAtTheEndsOfTheRange) {
  const std::vector<float> z = {0.0f, 0.0f, 1e-7f, 0.9999999f, 1.0f, 1.0f};
  OccTexel t = buildOcc(z);
  EXPECT_EQ(t.bits[0] & 1u, 1u);
  EXPECT_EQ(t.bits[3] >> 31, 1u);
  EXPECT_EQ(occCount(t, 0.0f), 0.0f);
  EXPECT_NEAR(occCount(t, 0.5f), 3.0f, 1e-4f);
  EXPECT_EQ(occCount(t, 1.0001f), 6.0f);
  expectWellBehaved([&](float d) { return occCount(t, d); }, 0.5f, 6.0f);
  expectWellBehaved([&](float d) { return occCount(t, d, false); }, 0.5f, 6.0f);
}

TEST(OccupancyMath, SlabBoundariesAreExactAndTheRestIsClose) {
  std::mt19937 rng(3);
  // A stray strand in front, then a dense clump (the paper's Figure 5 case).
  std::vector<float> z = {0.10f};
  std::normal_distribution<float> clump(0.5f, 0.03f);
  for (int i = 0; i < 4000; ++i) z.push_back(std::clamp(clump(rng), 0.3f, 0.9f));
  std::uniform_real_distribution<float> spread(0.3f, 0.9f);
  for (int i = 0; i < 1000; ++i) z.push_back(spread(rng));
  for (int slices : {32, 128, 512}) {
    double previous = 1e30;  // more slabs: closer to exact
    for (int slabs : {1, 4, 16}) {
      if (slabs > slices) continue;
      OccTexel t = buildOcc(z, slices, slabs);
      const float range = t.zMax - t.zMin;
      for (int b = 1; b < slabs; ++b) {
        const float at = t.zMin + range * float(b) / float(slabs);
        EXPECT_NEAR(occCount(t, at), exactCount(z, at), 2.0f) << b;
      }
      double sq = 0;
      for (int i = 1; i < 1000; ++i) {
        const float at = t.zMin + range * float(i) / 1000.0f;
        const double d = occCount(t, at) - exactCount(z, at);
        sq += d * d;
      }
      const double rmse = std::sqrt(sq / 999.0);
      EXPECT_LT(rmse, previous) << slices << " slices, " << slabs << " slabs";
      previous = rmse;
      // Every slice of the clump is occupied, so only the slab counts shape it.
      if (slabs == 16) {
        EXPECT_LT(rmse, 0.05 * double(z.size())) << slices << " slices";
      }
      expectWellBehaved([&](float d) { return occCount(t, d); }, 0.02f, float(z.size()));
      expectWellBehaved([&](float d) { return occCount(t, d, false); }, 0.02f, float(slices));
    }
  }
}

TEST(OccupancyMath, SlabsBeatOccupancyAloneOnAClump) {
  std::vector<float> z = {0.05f};
  for (int i = 0; i < 2000; ++i) z.push_back(0.6f + 0.1f * float(i) / 2000.0f);
  OccTexel t = buildOcc(z);
  double withSlabs = 0, bitsOnly = 0;
  for (int i = 1; i < 200; ++i) {
    const float at = float(i) / 200.0f;
    withSlabs += std::abs(occCount(t, at) - exactCount(z, at));
    bitsOnly += std::abs(occCount(t, at, false) - exactCount(z, at));
  }
  EXPECT_LT(withSlabs, bitsOnly);
}

TEST(OccupancyMath, VisibilityExtremes) {
  EXPECT_EQ(glsl::occupancyVisibility(0.0f, 1.0f), 1.0f);  // pow(0, 0) guarded
  EXPECT_EQ(glsl::occupancyVisibility(0.0f, 0.0f), 1.0f);
  EXPECT_EQ(glsl::occupancyVisibility(5.0f, 0.0f), 1.0f);
  EXPECT_EQ(glsl::occupancyVisibility(5.0f, 1.0f), 0.0f);
  EXPECT_EQ(glsl::occupancyVisibility(1e-3f, 1.0f), 0.0f);
  EXPECT_NEAR(glsl::occupancyVisibility(2.0f, 0.5f), 0.25f, 1e-6f);
  EXPECT_EQ(glsl::occupancyVisibility(-1.0f, 0.5f), 1.0f);
}

// ---------------------------------------------------------------- CPU: density clustering

struct DcTexel {
  float zMin = 2.0f, zMax = -2.0f;
  glm::vec4 n{0.0f}, s1{0.0f}, s2{0.0f}, centres{0.0f};
  int k = 4;
};

// The GPU's k-means, step for step: centres spread over the range, then per
// iteration assign every fragment and take the new means.
DcTexel buildDc(const std::vector<float>& z, int k = 4, int iterations = 2) {
  DcTexel t;
  t.k = k;
  for (float d : z) t.zMin = std::min(t.zMin, d), t.zMax = std::max(t.zMax, d);
  for (int it = 0; it < iterations; ++it) {
    for (int j = 0; j < k; ++j) {
      const float initial = glsl::dcInitialCentre(j, k, t.zMin, t.zMax);
      t.centres[j] = it == 0 ? initial : glsl::dcCentre(t.n[j], t.s1[j], t.zMin, initial);
    }
    t.n = t.s1 = t.s2 = glm::vec4(0.0f);
    for (float d : z) {
      const int j = glsl::dcNearest(d, t.centres, k);
      const float rel = std::max(d - t.zMin, 0.0f);
      t.n[j] += 1.0f;
      t.s1[j] += rel;
      t.s2[j] += rel * rel;
    }
  }
  return t;
}

float dcCount(const DcTexel& t, float z) {
  return glsl::dcCount(z, t.zMin, t.zMax, t.n, t.s1, t.s2, t.k);
}

TEST(DensityClusteringMath, EmptyTexelIsLit) {
  const DcTexel t = buildDc({});
  for (float z : {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f}) EXPECT_EQ(dcCount(t, z), 0.0f);
  expectWellBehaved([&](float z) { return dcCount(t, z); }, 0.5f, 0.0f);
}

TEST(DensityClusteringMath, OneFragmentAndZeroDepthRange) {
  for (std::size_t count : {std::size_t(1), std::size_t(5000)}) {
    const std::vector<float> z(count, 0.25f);
    const DcTexel t = buildDc(z);
    EXPECT_EQ(dcCount(t, 0.2f), 0.0f);
    EXPECT_EQ(dcCount(t, 0.25f), 0.0f);
    EXPECT_EQ(dcCount(t, 0.2501f), float(count));
    for (float alpha : {0.0f, 0.5f, 1.0f})
      expectWellBehaved([&](float d) { return dcCount(t, d); }, alpha, float(count));
  }
}

TEST(DensityClusteringMath, SeparatedClustersAreCountedWhole) {
  std::vector<float> z;
  for (int i = 0; i < 300; ++i) z.push_back(0.10f + 0.01f * float(i) / 300.0f);
  for (int i = 0; i < 700; ++i) z.push_back(0.80f + 0.01f * float(i) / 700.0f);
  const DcTexel t = buildDc(z, 2);
  EXPECT_EQ(t.n[0], 300.0f);
  EXPECT_EQ(t.n[1], 700.0f);
  EXPECT_EQ(dcCount(t, 0.05f), 0.0f);
  EXPECT_NEAR(dcCount(t, 0.5f), 300.0f, 1e-3f);
  EXPECT_NEAR(dcCount(t, 0.9f), 1000.0f, 1e-3f);
  // Inside a cluster: linear across mean +- sqrt(3) sd, half at the mean.
  const float mean = t.zMin + t.s1[1] / t.n[1];
  EXPECT_NEAR(dcCount(t, mean), 300.0f + 350.0f, 1.0f);
  expectWellBehaved([&](float d) { return dcCount(t, d); }, 0.1f, 1000.0f);
}

TEST(DensityClusteringMath, UniformFragmentsGiveALinearCount) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.2f, 0.6f);
  std::vector<float> z;
  for (int i = 0; i < 4000; ++i) z.push_back(u(rng));
  for (int k : {1, 2, 4}) {
    const DcTexel t = buildDc(z, k, 3);
    float total = 0;
    for (int j = 0; j < k; ++j) total += t.n[j];
    EXPECT_EQ(total, 4000.0f);
    for (float at : {0.25f, 0.4f, 0.55f}) EXPECT_NEAR(dcCount(t, at), exactCount(z, at), 150.0f);
    expectWellBehaved([&](float d) { return dcCount(t, d); }, 0.01f, 4000.0f);
  }
}

TEST(DensityClusteringMath, FragmentsAtTheEndsAndFarFromZero) {
  // Near depth 1 and packed tightly: the sums relative to the nearest depth
  // keep the deviation; the variance never goes negative.
  std::vector<float> z = {0.0f, 1.0f};
  for (int i = 0; i < 1000; ++i) z.push_back(0.999f + 1e-6f * float(i % 7));
  const DcTexel t = buildDc(z);
  EXPECT_EQ(dcCount(t, 0.0f), 0.0f);
  EXPECT_NEAR(dcCount(t, 0.5f), 1.0f, 1e-4f);
  EXPECT_NEAR(dcCount(t, 1.0001f), 1002.0f, 1e-3f);
  expectWellBehaved([&](float d) { return dcCount(t, d); }, 0.5f, 1002.0f);
  // Sums whose rounding would make the variance negative.
  EXPECT_EQ(glsl::dcClusterCount(0.5001f, 3.0f, 1.5f, 0.74999f), 3.0f);
  EXPECT_EQ(glsl::dcClusterCount(0.5f, 3.0f, 1.5f, 0.74999f), 0.0f);
}

TEST(DensityClusteringMath, NearestAndCentres) {
  const glm::vec4 c(0.1f, 0.4f, 0.7f, 0.9f);
  EXPECT_EQ(glsl::dcNearest(0.0f, c, 4), 0);
  EXPECT_EQ(glsl::dcNearest(0.56f, c, 4), 2);
  EXPECT_EQ(glsl::dcNearest(0.95f, c, 4), 3);
  EXPECT_EQ(glsl::dcNearest(0.95f, c, 2), 1);  // only the first k count
  EXPECT_EQ(glsl::dcNearest(0.25f, c, 4), 0);  // a tie goes to the lower index
  EXPECT_FLOAT_EQ(glsl::dcInitialCentre(0, 4, 0.0f, 1.0f), 0.125f);
  EXPECT_FLOAT_EQ(glsl::dcInitialCentre(3, 4, 0.0f, 1.0f), 0.875f);
  EXPECT_FLOAT_EQ(glsl::dcInitialCentre(1, 2, 0.5f, 0.5f), 0.5f);
  EXPECT_EQ(glsl::dcCentre(0.0f, 0.0f, 0.2f, 0.33f), 0.33f);
  EXPECT_FLOAT_EQ(glsl::dcCentre(4.0f, 0.4f, 0.2f, 0.33f), 0.3f);
}

// ---------------------------------------------------------------- GPU, both backends

struct Frame {
  std::vector<float> color, visibility;
  std::vector<std::string> warnings;
  std::size_t shadowBytes = 0;
};

Frame render(Device& dev, const std::string& sceneSpec, const std::string& shadowSpec,
             uint32_t size = 64, Primitive primitive = Primitive::Lines) {
  const Scene scene = makeScene(Spec::parse(sceneSpec));
  RenderSettings s = sbtest::fittedSettings(scene, size);
  s.primitive = primitive;
  std::size_t before = 0;  // the device keeps earlier renderers' resources
  for (const auto& a : dev.allocations())
    if (a.owner == Owner::Shadow) before += a.bytes;
  Renderer r(dev, scene, s, makeShadowTechnique(Spec::parse(shadowSpec)),
             makeOitTechnique(Spec::parse("none")), {Output::Color, Output::Visibility});
  r.renderFrame();
  Frame f;
  f.color = floats(r.readColor());
  f.visibility = floats(r.readVisibility());
  f.warnings = r.warnings();
  for (const auto& a : dev.allocations())
    if (a.owner == Owner::Shadow) f.shadowBytes += a.bytes;
  f.shadowBytes -= before;
  return f;
}

const char* kHair = "straight:strands=600,points=10,alpha=0.5,shadow_alpha=0.3";
const char* kHairNoHead = "curly:strands=300,points=16,alpha=0.5,head=0";

const std::vector<std::string>& allOptions() {
  static const std::vector<std::string> specs = {
      "occupancy:size=64",
      "occupancy:size=64,jitter=on",
      "occupancy:size=64,slab_map=off",
      "occupancy:size=64,slices=32,slabs=1",
      "occupancy:size=64,slices=96,slabs=3",
      "occupancy:size=64,slices=256,slabs=8",
      "occupancy:size=64,slices=512,slabs=4",
      "occupancy:size=64,slices=512,slab_map=off,bias=0",
      "occupancy:size=64,slices=512,slabs=8",  // 6 textures once: more than the bindings held
      // The cap: 8 layers of bits and of slabs, each layer a colour attachment.
      "occupancy:size=64,slices=1024,slabs=32",
      "occupancy:size=64,slices=1024,slab_map=off",
      "dc:size=64",
      "dc:size=64,clusters=1,iterations=1",
      "dc:size=64,clusters=2,iterations=3",
      "dc:size=64,clusters=3,bias=0",
      // Two layers of every map; 8 clusters fill 6 colour attachments.
      "dc:size=64,clusters=5,iterations=3",
      "dc:size=64,clusters=8",
  };
  return specs;
}

class DcOccupancyGpu : public sbtest::BackendTest {};

void expectFinite(const Frame& f, const std::string& what) {
  std::size_t lit = 0, surfaces = 0;
  for (float x : f.color) ASSERT_TRUE(std::isfinite(x)) << what << ": colour";
  for (float v : f.visibility) {
    ASSERT_TRUE(std::isfinite(v)) << what << ": visibility";
    if (v < 0.0f) continue;  // background
    ++surfaces;
    EXPECT_LE(v, 1.0f) << what;
    lit += v > 0.0f;
  }
  EXPECT_GT(surfaces, 0u) << what;
  EXPECT_GT(lit, 0u) << what;
  EXPECT_TRUE(f.warnings.empty()) << what << ": " << f.warnings.front();
}

TEST_P(DcOccupancyGpu, EveryOptionRendersWithoutNaN) {
  for (const std::string& spec : allOptions()) {
    for (const char* scene : {kHair, kHairNoHead}) {
      SCOPED_TRACE(spec + " on " + scene);
      expectFinite(render(*dev_, scene, spec), spec);
    }
  }
  // Ribbons.
  expectFinite(render(*dev_, kHair, "occupancy:size=64", 64, Primitive::Ribbons), "ribbons");
  expectFinite(render(*dev_, kHair, "dc:size=64", 64, Primitive::Ribbons), "ribbons");
}

TEST_P(DcOccupancyGpu, OccupancyMapsTakeTenMiB) {
  const Frame f = render(*dev_, "straight:strands=200,points=8,head=0", "occupancy:size=512");
  EXPECT_EQ(f.shadowBytes, 10u * 1024 * 1024);
  std::cout << "[ measured ] " << GetParam() << " occupancy 512x512 shadow bytes " << f.shadowBytes
            << "\n";
  const Frame bitsOnly =
      render(*dev_, "straight:strands=200,points=8,head=0", "occupancy:size=512,slab_map=off");
  EXPECT_EQ(bitsOnly.shadowBytes, 6u * 1024 * 1024);
  const Frame dc = render(*dev_, "straight:strands=200,points=8,head=0", "dc:size=512");
  EXPECT_EQ(dc.shadowBytes, 18u * 1024 * 1024);  // RG32F range + 4 RGBA32F
  // 8 clusters: the four RGBA32F maps are arrays of two layers.
  const Frame dc8 = render(*dev_, "straight:strands=200,points=8,head=0", "dc:size=512,clusters=8");
  EXPECT_EQ(dc8.shadowBytes, 34u * 1024 * 1024);
}

TEST_P(DcOccupancyGpu, CloserToExactThanAShadowMap) {
  for (const char* scene : {kHair, kHairNoHead}) {
    SCOPED_TRACE(scene);
    const Frame exact = render(*dev_, scene, "exact:size=64,method=abuffer");
    const double hard =
        compareVisibility(render(*dev_, scene, "shadowmap:size=64").visibility, exact.visibility)
            .rmse;
    const double occ =
        compareVisibility(render(*dev_, scene, "occupancy:size=64").visibility, exact.visibility)
            .rmse;
    const double occBits =
        compareVisibility(render(*dev_, scene, "occupancy:size=64,slab_map=off").visibility,
                          exact.visibility)
            .rmse;
    const double dc =
        compareVisibility(render(*dev_, scene, "dc:size=64").visibility, exact.visibility).rmse;
    std::cout << "[ measured ] " << GetParam() << " " << scene << " visibility rmse: shadowmap "
              << hard << ", occupancy " << occ << ", occupancy slab_map=off " << occBits << ", dc "
              << dc << "\n";
    EXPECT_LT(occ, hard);
    EXPECT_LT(occ, occBits);
    EXPECT_LT(dc, hard);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, DcOccupancyGpu, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

TEST(DcOccupancyApis, GlAndVulkanAgree) {
  auto [gl, vk, unavailable] = sbtest::makeBothBackends();
  if (!unavailable.empty()) GTEST_SKIP() << unavailable;
  const std::size_t messages = validationMessageCount();
  for (const std::string& spec : allOptions()) {
    for (const char* scene : {kHair, kHairNoHead}) {
      SCOPED_TRACE(spec + " on " + scene);
      const Frame a = render(*gl, scene, spec);
      const Frame b = render(*vk, scene, spec);
      ASSERT_EQ(a.color.size(), b.color.size());
      ASSERT_EQ(a.visibility.size(), b.visibility.size());
      float color = 0, visibility = 0;
      for (std::size_t i = 0; i < a.color.size(); ++i)
        color = std::max(color, std::abs(a.color[i] - b.color[i]));
      for (std::size_t i = 0; i < a.visibility.size(); ++i)
        visibility = std::max(visibility, std::abs(a.visibility[i] - b.visibility[i]));
      std::cout << "[ measured ] " << spec << " " << scene << ": GL-Vulkan max abs colour " << color
                << ", visibility " << visibility << "\n";
      EXPECT_LT(color, 2e-3f);
      EXPECT_LT(visibility, 2e-3f);
    }
  }
  EXPECT_EQ(validationMessageCount(), messages) << "Vulkan validation messages";
}

TEST(DcOccupancyOptions, InvalidOptionsAreRejected) {
  for (const char* bad : {"occupancy:slices=100", "occupancy:slices=16", "occupancy:slices=1056",
                          "occupancy:slices=128,slabs=3", "occupancy:slices=1024,slabs=64",
                          "occupancy:slices=2048", "occupancy:jitter=maybe", "occupancy:slab_map=1",
                          "dc:clusters=9", "dc:clusters=0", "dc:iterations=0", "dc:layers=3"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(makeShadowTechnique(Spec::parse(bad)), InputError);
  }
  try {
    makeShadowTechnique(Spec::parse("occupancy:slices=100"));
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("multiple of 32"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(makeShadowTechnique(Spec::parse("occupancy:slices=512,slab_map=off")));
  EXPECT_NO_THROW(makeShadowTechnique(Spec::parse("occupancy:slices=384,slabs=4")));
  EXPECT_NO_THROW(makeShadowTechnique(Spec::parse("dc:clusters=4,iterations=5")));
}

}  // namespace
}  // namespace sb
