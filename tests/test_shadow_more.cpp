// Shadow techniques beyond the seed papers, judged against the
// exact visibility: deep shadow maps (Lokovic & Veach 2000). The math shared
// with the GLSL is tested on the CPU against a brute-force check of the
// epsilon bound; the GPU tests render both backends against the exact
// reference and print the figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "gpu_test_util.h"
#include "harness/measures/probe/probe.h"
#include "harness/render.h"
#include "techniques/adsm/adsm_math.h"
#include "techniques/dsm/dsm_math.h"
#include "techniques/fom/fom_math.h"

namespace sb::glsl {
// The lookup filter kernels of opacity_filter.glsl over a CPU opacity field.
using glm::clamp;
using glm::floor;
using glm::ivec2;
using glm::mix;
using glm::vec2;
inline float (*filterFieldCpu)(ivec2) = nullptr;
#define SB_FILTER_OPACITY(t) filterFieldCpu(t)
#include "render/common/opacity_filter.glsl"
#undef SB_FILTER_OPACITY
}  // namespace sb::glsl

namespace sb {
namespace {

// --- deep shadow maps: the compression (techniques/dsm/dsm_math.glsl) ---

// The exact visibility of a texel at depth z: t^(fragments strictly in front).
float exactVisibility(const std::vector<float>& sorted, float t, float z) {
  const auto n = std::lower_bound(sorted.begin(), sorted.end(), z) - sorted.begin();
  return std::pow(t, float(n));
}

// Brute force: the largest |curve - exact| over every depth, both sides of it,
// the midpoints between depths, in front of the first and behind the last,
// and 200 evenly spread depths.
float maxCurveError(const std::vector<glm::vec2>& nodes, const std::vector<float>& sorted,
                    float t) {
  std::vector<float> zs;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    zs.push_back(sorted[i]);
    zs.push_back(std::nextafter(sorted[i], 2.0f));
    zs.push_back(std::nextafter(sorted[i], -1.0f));
    if (i + 1 < sorted.size()) zs.push_back(0.5f * (sorted[i] + sorted[i + 1]));
  }
  zs.push_back(sorted.front() - 0.01f);
  zs.push_back(sorted.back() + 0.01f);
  for (int i = 0; i <= 200; ++i) zs.push_back(float(i) / 200.0f);
  float worst = 0;
  for (float z : zs)
    worst = std::max(worst, std::abs(dsmEvaluate(nodes, z) - exactVisibility(sorted, t, z)));
  return worst;
}

std::vector<float> randomDepths(std::mt19937& rng, int n) {
  std::uniform_real_distribution<float> u(0.05f, 0.95f);
  std::vector<float> d;
  for (int i = 0; i < n; ++i) {
    d.push_back(u(rng));
    if (i % 7 == 3) d.push_back(d.back());  // fragments at one depth
  }
  std::sort(d.begin(), d.end());
  return d;
}

TEST(DsmMath, EpsilonZeroIsTheStepFunctionNodeForNode) {
  const DsmCurve c = dsmCompress({0.1f, 0.2f, 0.3f}, 0.5f, 0.0f);
  const std::vector<glm::vec2> want = {{0.1f, 1.0f},  {0.1f, 0.5f},  {0.2f, 0.5f},
                                       {0.2f, 0.25f}, {0.3f, 0.25f}, {0.3f, 0.125f}};
  ASSERT_EQ(c.nodes.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_FLOAT_EQ(c.nodes[i].x, want[i].x) << i;
    EXPECT_NEAR(c.nodes[i].y, want[i].y, 1e-6f) << i;
  }
  // A point exactly at a fragment's depth sees it as behind (as exact does).
  EXPECT_FLOAT_EQ(dsmEvaluate(c.nodes, 0.2f), 0.5f);
  EXPECT_FLOAT_EQ(dsmEvaluate(c.nodes, 0.25f), 0.25f);
  EXPECT_FLOAT_EQ(dsmEvaluate(c.nodes, 0.05f), 1.0f);
  EXPECT_FLOAT_EQ(dsmEvaluate(c.nodes, 0.9f), 0.125f);
}

TEST(DsmMath, EpsilonZeroReproducesRandomTexels) {
  std::mt19937 rng(7);
  for (int texel = 0; texel < 300; ++texel) {
    const std::vector<float> d = randomDepths(rng, 1 + texel % 40);
    for (float t : {0.5f, 0.9f, 0.2f}) {
      const DsmCurve c = dsmCompress(d, t, 0.0f);
      EXPECT_FALSE(c.truncated);
      EXPECT_LE(maxCurveError(c.nodes, d, t), 1e-6f) << "texel " << texel << " t " << t;
    }
  }
}

// The paper's guarantee, checked by brute force on random texels: the curve
// is within epsilon of the exact function everywhere, never rises, and keeps
// fewer nodes as epsilon grows.
TEST(DsmMath, CurveStaysWithinEpsilonAndFalls) {
  std::mt19937 rng(11);
  std::size_t nodes[4] = {0, 0, 0, 0};
  const float epsilons[4] = {0.0f, 0.01f, 0.05f, 0.2f};
  for (int texel = 0; texel < 300; ++texel) {
    const std::vector<float> d = randomDepths(rng, 1 + texel % 60);
    for (float t : {0.5f, 0.85f, 0.97f}) {
      for (int e = 0; e < 4; ++e) {
        const DsmCurve c = dsmCompress(d, t, epsilons[e]);
        nodes[e] += c.nodes.size();
        EXPECT_LE(maxCurveError(c.nodes, d, t), epsilons[e] + 1e-6f)
            << "texel " << texel << " t " << t << " epsilon " << epsilons[e];
        for (std::size_t i = 1; i < c.nodes.size(); ++i) {
          EXPECT_GE(c.nodes[i].x, c.nodes[i - 1].x);
          EXPECT_LE(c.nodes[i].y, c.nodes[i - 1].y + 1e-7f);
        }
      }
    }
  }
  std::cout << "[ measured ] nodes kept over 900 random texels, epsilon 0 / 0.01 / 0.05 / 0.2: "
            << nodes[0] << " / " << nodes[1] << " / " << nodes[2] << " / " << nodes[3] << "\n";
  EXPECT_LT(nodes[1], nodes[0]);
  EXPECT_LT(nodes[2], nodes[1]);
  EXPECT_LT(nodes[3], nodes[2]);
}

// The brute-force check is not vacuous: it catches a curve beyond its bound
// (compressed at 0.1, checked against 0.05) and a curve missing one of its nodes.
TEST(DsmMath, BruteForceCheckCatchesAWrongCurve) {
  std::mt19937 rng(3);
  const std::vector<float> d = randomDepths(rng, 40);
  const DsmCurve loose = dsmCompress(d, 0.85f, 0.1f);
  EXPECT_GT(maxCurveError(loose.nodes, d, 0.85f), 0.05f);
  DsmCurve exact = dsmCompress(d, 0.85f, 0.0f);
  exact.nodes.erase(exact.nodes.begin() + 3);  // the step down at the second depth
  EXPECT_GT(maxCurveError(exact.nodes, d, 0.85f), 0.05f);
}

TEST(DsmMath, MaxNodesCutsTheCurveAndSaysSo) {
  std::mt19937 rng(5);
  const std::vector<float> d = randomDepths(rng, 30);
  const DsmCurve c = dsmCompress(d, 0.5f, 0.0f, 8);
  EXPECT_TRUE(c.truncated);
  EXPECT_EQ(c.nodes.size(), 8u);
  EXPECT_FALSE(dsmCompress(d, 0.5f, 0.0f, 2 * d.size()).truncated);
}

// --- approximated deep shadows (TressFX): techniques/adsm/adsm_math.glsl ---

TEST(AdsmMath, OneFiberAsSoonAsBehindTheFrontThenOnePerFiberDepth) {
  EXPECT_FLOAT_EQ(glsl::adsmVisibility(0.0f, 0.01f, 0.5f), 1.0f);
  EXPECT_NEAR(glsl::adsmVisibility(1e-7f, 0.01f, 0.5f), 0.5f, 1e-4f);
  EXPECT_NEAR(glsl::adsmVisibility(0.01f, 0.01f, 0.5f), 0.25f, 1e-6f);
  EXPECT_NEAR(glsl::adsmVisibility(0.03f, 0.01f, 0.5f), 0.0625f, 1e-6f);
  float prev = 1.0f;
  for (int i = 0; i < 100; ++i) {  // falls with depth, stays in [0, 1]
    const float v = glsl::adsmVisibility(float(i) * 0.003f, 0.01f, 0.3f);
    EXPECT_LE(v, prev);
    EXPECT_GE(v, 0.0f);
    prev = v;
  }
  EXPECT_FLOAT_EQ(glsl::adsmVisibility(0.05f, 0.01f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(glsl::adsmVisibility(0.05f, 0.01f, 1.0f), 0.0f);
}

TEST(AdsmMath, KernelIsTressFxsGaussian) {
  // sigma = (5 / 2) / 2.4 for the 5-tap kernel.
  const float sigma = 2.5f / 2.4f;
  EXPECT_FLOAT_EQ(glsl::adsmKernelWeight(0, 0, 5), 1.0f);
  EXPECT_NEAR(glsl::adsmKernelWeight(2, 1, 5), std::exp(-5.0f / (2 * sigma * sigma)), 1e-6f);
  EXPECT_FLOAT_EQ(glsl::adsmKernelWeight(-1, 2, 5), glsl::adsmKernelWeight(2, -1, 5));
}

// --- Fourier opacity maps: techniques/fom/fom_math.glsl ---

// A texel's coefficients from fragments at normalised depths d, n frequencies.
std::vector<float> fomCoefficients(const std::vector<float>& depths, int n, float alpha) {
  std::vector<float> c(std::size_t(2 * n + 1), 0.0f);
  for (float d : depths)
    for (int j = 0; j <= 2 * n; ++j)
      c[std::size_t(j)] += glsl::fomCoefficient(j, d, glsl::fomAbsorption(alpha));
  return c;
}

// RMSE of the clamped reconstruction against the exact visibility over d in
// [0, 1], and the largest unclamped exp(-I) (ringing above 1).
struct FomError {
  double rmse = 0;
  float unclampedMax = 0;
};
FomError fomError(const std::vector<float>& sorted, int n, float alpha) {
  const std::vector<float> c = fomCoefficients(sorted, n, alpha);
  glsl::fomCoeffCpu = c.data();
  FomError e;
  double sum = 0;
  const int samples = 1000;
  for (int i = 0; i < samples; ++i) {
    const float d = (float(i) + 0.5f) / samples;
    const float I = glsl::fomOpticalDepth(d, n);
    const float t = glsl::fomTransmittance(I);
    EXPECT_GE(t, 0.0f);
    EXPECT_LE(t, 1.0f);
    e.unclampedMax = std::max(e.unclampedMax, std::exp(-I));
    const double diff = t - exactVisibility(sorted, 1.0f - alpha, d);
    sum += diff * diff;
  }
  e.rmse = std::sqrt(sum / samples);
  return e;
}

TEST(FomMath, OneFragmentIsAStepTheSeriesApproaches) {
  const std::vector<float> c = fomCoefficients({0.5f}, 64, 0.5f);
  glsl::fomCoeffCpu = c.data();
  EXPECT_FLOAT_EQ(glsl::fomOpticalDepth(0.0f, 64), 0.0f);
  EXPECT_NEAR(glsl::fomOpticalDepth(1.0f, 64), std::log(2.0f), 1e-5f);         // all of it
  EXPECT_NEAR(glsl::fomOpticalDepth(0.5f, 64), 0.5f * std::log(2.0f), 1e-4f);  // half way up
  EXPECT_NEAR(glsl::fomOpticalDepth(0.3f, 64), 0.0f, 0.01f);
  EXPECT_NEAR(glsl::fomOpticalDepth(0.7f, 64), std::log(2.0f), 0.01f);
}

// The error falls as coefficients rise (random texels), the clamped
// transmittance stays in [0, 1], and without the clamp it rings above 1.
TEST(FomMath, ErrorFallsWithCoefficientsAndClampingBoundsTheRinging) {
  std::mt19937 rng(13);
  double err[3] = {0, 0, 0};
  const int ns[3] = {4, 8, 16};
  float ringing = 0;
  for (int texel = 0; texel < 100; ++texel) {
    const std::vector<float> d = randomDepths(rng, 1 + texel % 12);
    for (int i = 0; i < 3; ++i) {
      const FomError e = fomError(d, ns[i], 0.3f);
      err[i] += e.rmse;
      ringing = std::max(ringing, e.unclampedMax);
    }
  }
  std::cout << "[ measured ] mean RMSE over 100 random texels, 4 / 8 / 16 coefficients: "
            << err[0] / 100 << " / " << err[1] / 100 << " / " << err[2] / 100
            << "; largest unclamped exp(-I) " << ringing << "\n";
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
  EXPECT_GT(ringing, 1.0f);
}

// --- the dom / osm lookup filters: render/common/opacity_filter.glsl ---

TEST(OpacityFilter, KernelsOnKnownFields) {
  // A linear ramp in x: bilinear reproduces it between texel centres, and the
  // symmetric kernels keep the value at the point.
  glsl::filterFieldCpu = [](glsl::ivec2 t) { return float(t.x); };
  const int size = 32;
  const glm::vec2 uv(10.25f / size, 7.5f / size);  // texel units (10.25, 7.5)
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(uv, size, glsl::kFilterNone), 10.0f);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(uv, size, glsl::kFilterPcf2x2), 9.75f);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(uv, size, glsl::kFilterPcf6x4), 9.75f);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(uv, size, glsl::kFilterPcf6x6), 9.5f);
  // A single bright texel: spread over 36 texels by pcf6x6, 1/9-weighted
  // pcf2x2 samples by pcf6x4, untouched by none away from it.
  glsl::filterFieldCpu = [](glsl::ivec2 t) { return t == glsl::ivec2(16, 16) ? 36.0f : 0.0f; };
  const glm::vec2 centre(16.5f / size, 16.5f / size);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(centre, size, glsl::kFilterNone), 36.0f);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(centre, size, glsl::kFilterPcf2x2), 36.0f);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(centre, size, glsl::kFilterPcf6x4), 4.0f);
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(centre, size, glsl::kFilterPcf6x6), 1.0f);
  // Edges clamp: a constant field stays constant at the map's corner.
  glsl::filterFieldCpu = [](glsl::ivec2) { return 3.0f; };
  for (int k = 0; k < 4; ++k)
    EXPECT_FLOAT_EQ(glsl::filteredOpacity(glm::vec2(0.0f), size, k), 3.0f) << k;
}

// ---- the OSM paper's 3x3 averaging kernel ----

TEST(OsmBox3x3, AveragesThePointsTexelAndItsEightNeighbours) {
  const int size = 32;
  // A ramp in x: the symmetric average keeps the point's texel value.
  glsl::filterFieldCpu = [](glsl::ivec2 t) { return float(t.x); };
  EXPECT_FLOAT_EQ(
      glsl::filteredOpacity(glm::vec2(10.25f, 7.5f) / float(size), size, glsl::kFilterBox3x3),
      10.0f);
  // One bright texel: 1/9 of it in each of the 9 texels around it, nothing
  // two texels away (pcf6x6 spreads it over 36: a different kernel).
  glsl::filterFieldCpu = [](glsl::ivec2 t) { return t == glsl::ivec2(16, 16) ? 36.0f : 0.0f; };
  for (const glm::vec2 p : {glm::vec2(16.5f, 16.5f), glm::vec2(17.5f, 16.5f),
                            glm::vec2(15.5f, 15.5f), glm::vec2(17.9f, 17.1f)})
    EXPECT_FLOAT_EQ(glsl::filteredOpacity(p / float(size), size, glsl::kFilterBox3x3), 4.0f);
  EXPECT_FLOAT_EQ(
      glsl::filteredOpacity(glm::vec2(18.5f, 16.5f) / float(size), size, glsl::kFilterBox3x3),
      0.0f);
  EXPECT_FLOAT_EQ(
      glsl::filteredOpacity(glm::vec2(16.5f, 16.5f) / float(size), size, glsl::kFilterPcf6x6),
      1.0f);
  // Edges clamp: a constant field stays constant at the corner.
  glsl::filterFieldCpu = [](glsl::ivec2) { return 3.0f; };
  EXPECT_FLOAT_EQ(glsl::filteredOpacity(glm::vec2(0.0f), size, glsl::kFilterBox3x3), 3.0f);
  EXPECT_EQ(makeShadowTechnique(Spec::parse("osm:filter=box3x3"))->name(), "osm");
}

// --- the ray invariant for a technique that does not promise to fall (fom) ---

TEST(ShadowMoreInvariants, RayMayRiseOnlyWhereTheTechniqueSaysSo) {
  std::vector<InvariantFailure> f;
  checkRay({1.0f, 0.5f, 0.6f}, "probe (fom)", f, /*monotone=*/false);
  EXPECT_TRUE(f.empty());
  checkRay({1.0f, 0.5f, 0.6f}, "probe (fom)", f);
  EXPECT_EQ(f.size(), 1u);
  checkRay({1.0f, 1.5f}, "probe (fom)", f, false);  // [0, 1] still holds
  EXPECT_EQ(f.size(), 2u);
  EXPECT_FALSE(makeShadowTechnique(Spec::parse("fom"))->monotone());
  EXPECT_TRUE(makeShadowTechnique(Spec::parse("dsm"))->monotone());
  EXPECT_TRUE(makeShadowTechnique(Spec::parse("adsm"))->monotone());
}

// --- GPU: both backends against the exact visibility ---

class ShadowMore : public sbtest::ProbedShadowTest {
 protected:
  static double probeMinExact(const RenderResult& out) {
    const std::vector<float>& exact = out.measure<ProbeResult>()->exact;
    return *std::min_element(exact.begin(), exact.end());
  }
};

TEST_P(ShadowMore, DsmWithEpsilonZeroEqualsExact) {
  const RenderResult out =
      run(request("straight:strands=1500,points=16", "dsm:epsilon=0,size=128,max_nodes=65536"));
  EXPECT_GT(out.visibilityError->pixels, 500u);
  EXPECT_LT(probeMinExact(out), 0.5);  // the ray crosses hair
  EXPECT_LE(out.visibilityError->max, 1e-5);
  EXPECT_LE(probeMaxError(out), 1e-5);
  // The same comparison fails when the compression is allowed an error.
  const RenderResult loose =
      run(request("straight:strands=1500,points=16", "dsm:epsilon=0.1,size=128"));
  EXPECT_GT(loose.visibilityError->max, 1e-5);
  EXPECT_LT(counter(loose, "dsm_nodes_mean"), counter(out, "dsm_nodes_mean"));
}

TEST_P(ShadowMore, DsmErrorIsWithinEpsilonAtEveryProbedPoint) {
  for (const std::string scene : {"curly:strands=300", "stray:strands=1500"}) {
    for (const double eps : {0.02, 0.1}) {
      const RenderResult out =
          run(request(scene, "dsm:epsilon=" + std::to_string(eps) + ",size=128"));
      EXPECT_LT(probeMinExact(out), 0.9) << scene;  // the ray crosses hair
      EXPECT_LE(probeMaxError(out), eps + 1e-5) << scene;
      EXPECT_LE(out.visibilityError->max, eps + 1e-5) << scene;
      std::cout << "[ measured ] nodes per texel min/mean/max " << counter(out, "dsm_nodes_min")
                << "/" << counter(out, "dsm_nodes_mean") << "/" << counter(out, "dsm_nodes_max")
                << ", kept " << counter(out, "dsm_kept_bytes") << " of "
                << counter(out, "dsm_slot_bytes") << " bytes\n";
    }
  }
}

TEST_P(ShadowMore, DsmRejectsBadOptionsNamingThem) {
  RenderRequest r = request("straight:strands=10", "dsm:epsilon=2");
  try {
    runRender(r);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("epsilon"), std::string::npos) << e.what();
  }
  r.shadow = "dsm:max_nodes=1";
  EXPECT_THROW(runRender(r), InputError);
}

// Fourier opacity maps on straight hair: the visibility error falls from 4 to
// 16 coefficients (the paper's claim: more coefficients, less ringing).
TEST_P(ShadowMore, FomErrorFallsAsCoefficientsRise) {
  double prev = 1e9;
  for (const int n : {4, 8, 16}) {
    const RenderResult out = run(request("straight:strands=1500,points=16",
                                         "fom:size=128,coefficients=" + std::to_string(n)));
    EXPECT_LT(out.visibilityError->rmse, prev) << n;
    prev = out.visibilityError->rmse;
  }
}

// The engines' approximations render on both backends within their invariants
// (visibility in [0, 1], non-increasing along the probe ray, finite maps); the
// errors against exact are printed for the README table, not ordered (the
// issue claims no ordering for them).
TEST_P(ShadowMore, EngineApproximationsRenderWithinTheirInvariants) {
  for (const std::string shadow :
       {"adsm:size=128", "adsm:size=128,kernel=1", "dom:layers=3,size=128,spacing=power",
        "dom:layers=3,size=128,filter=pcf2x2", "dom:layers=3,size=128,filter=pcf6x4",
        "dom:layers=3,size=128,filter=pcf6x6", "osm:maps=16,size=128,filter=pcf6x4"}) {
    const RenderResult out = run(request("stray:strands=1500", shadow));
    EXPECT_GT(out.visibilityError->rmse, 0.0) << shadow;  // approximations, not exact
  }
}

// A wider kernel blurs: on the same scene, pcf6x6 changes dom's visibility
// more than pcf2x2 does (measured against filter=none).
TEST_P(ShadowMore, DomFiltersBlurMoreAsTheyWiden) {
  auto visibility = [&](const std::string& shadow) {
    return sbtest::floats(run(request("stray:strands=1500", shadow)).visibility);
  };
  const std::vector<float> none = visibility("dom:layers=3,size=128");
  const std::vector<float> narrow = visibility("dom:layers=3,size=128,filter=pcf2x2");
  const std::vector<float> wide = visibility("dom:layers=3,size=128,filter=pcf6x6");
  const VisibilityError dn = compareVisibility(narrow, none), dw = compareVisibility(wide, none);
  std::cout << "[ measured ] dom change from filter=none: pcf2x2 RMSE " << dn.rmse
            << ", pcf6x6 RMSE " << dw.rmse << "\n";
  EXPECT_GT(dn.rmse, 0.0);
  EXPECT_GT(dw.rmse, dn.rmse);
}

INSTANTIATE_TEST_SUITE_P(Backends, ShadowMore, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// GL and Vulkan render the new techniques alike (visibility within 1e-4).
TEST(ShadowMoreParity, GlAndVulkanAgree) {
  const sbtest::BothBackends both = sbtest::makeBothBackends();
  if (!both.unavailable.empty()) GTEST_SKIP() << both.unavailable;
  sbtest::expectShadowParity(
      both, {"dsm:epsilon=0.02,size=128", "adsm:size=128", "fom:size=128,coefficients=16",
             "dom:layers=3,size=128,spacing=power,filter=pcf6x4"});
}

}  // namespace
}  // namespace sb
