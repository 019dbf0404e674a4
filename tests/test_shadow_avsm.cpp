// Adaptive volumetric shadow maps (Salvi et al. 2010): the math shared with the GLSL is tested
// on the CPU (the node removal against a brute-force search of the least area change), and both
// backends render against the exact visibility. (voxel's tests: techniques/voxel/test_voxel.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "gpu_test_util.h"
#include "harness/invariants.h"
#include "harness/render.h"
#include "techniques/avsm/avsm_math.h"

namespace sb {
namespace {

using glsl::AvsmCurve;

// --- AVSM: the curve (techniques/avsm/avsm_math.glsl) ---

AvsmCurve streamed(const std::vector<float>& depths, float t, int budget, int* removed = nullptr) {
  AvsmCurve c = AvsmCurve{};
  int r = 0;
  for (float d : depths) r += avsmStream(c, d, t, budget);
  if (removed) *removed = r;
  return c;
}

float lookup(AvsmCurve c, float z) { return avsmValue(c, z, false); }

// Area under the piecewise-linear curve between its first and last node.
double area(const std::vector<glm::vec2>& n) {
  double a = 0;
  for (std::size_t i = 1; i < n.size(); ++i)
    a += 0.5 * double(n[i].x - n[i - 1].x) * double(n[i].y + n[i - 1].y);
  return a;
}

// Brute force: the interior node whose removal changes the area least (the
// frontmost of equals), by integrating the curve with and without each.
int leastAreaNode(const AvsmCurve& c) {
  const std::vector<glm::vec2> all(c.n, c.n + c.count);
  const double full = area(all);
  int best = -1;
  double bestChange = 0;
  for (int i = 1; i + 1 < c.count; ++i) {
    std::vector<glm::vec2> without = all;
    without.erase(without.begin() + i);
    const double change = std::abs(area(without) - full);
    if (best < 0 || change < bestChange - 1e-12) {
      best = i;
      bestChange = change;
    }
  }
  return best;
}

// A random non-increasing curve of `count` nodes (first at transmittance 1).
AvsmCurve randomCurve(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> x(count), y(count);
  for (float& v : x) v = u(rng);
  for (float& v : y) v = u(rng);
  std::sort(x.begin(), x.end());
  std::sort(y.begin(), y.end(), std::greater<float>());
  y[0] = 1.0f;
  AvsmCurve c = AvsmCurve{};
  for (int i = 0; i < count; ++i) c.n[i] = {x[i], y[i]};
  c.count = count;
  return c;
}

TEST(AvsmMath, RemovalPicksTheLeastAreaNodeAsABruteForceSearch) {
  std::mt19937 rng(15);
  for (int trial = 0; trial < 2000; ++trial) {
    AvsmCurve c = randomCurve(rng, 4 + trial % 15);
    const int expected = leastAreaNode(c);
    const AvsmCurve before = c;
    const int removed = avsmRemoveOne(c);
    ASSERT_EQ(removed, expected) << "trial " << trial;
    // The curve lost exactly that node, the others unmoved.
    ASSERT_EQ(c.count, before.count - 1);
    for (int i = 0, j = 0; i < before.count; ++i) {
      if (i == removed) continue;
      ASSERT_EQ(c.n[j].x, before.n[i].x);
      ASSERT_EQ(c.n[j].y, before.n[i].y);
      ++j;
    }
  }
}

// The brute-force comparison can fail: a curve whose least-area node is the
// last interior one, against a removal that took the first.
TEST(AvsmMath, BruteForceCheckCatchesAWrongRemoval) {
  AvsmCurve c = AvsmCurve{};
  c.count = 4;
  c.n[0] = {0.0f, 1.0f};
  c.n[1] = {0.1f, 0.2f};   // a deep dent: large area change
  c.n[2] = {0.5f, 0.15f};  // nearly on the line from 1 to 3
  c.n[3] = {0.9f, 0.1f};
  EXPECT_EQ(leastAreaNode(c), 2);
  EXPECT_NE(leastAreaNode(c), 1);
  EXPECT_EQ(avsmRemoveOne(c), 2);
}

TEST(AvsmMath, OneFragmentIsAStepAtItsDepth) {
  const AvsmCurve c = streamed({0.4f}, 0.25f, 8);
  ASSERT_EQ(c.count, 2);
  EXPECT_EQ(lookup(c, 0.1f), 1.0f);
  EXPECT_EQ(lookup(c, 0.4f), 1.0f);  // a fragment at the receiver's depth does not shadow it
  EXPECT_EQ(lookup(c, std::nextafter(0.4f, 1.0f)), 0.25f);
  EXPECT_EQ(lookup(c, 0.9f), 0.25f);
}

// Fewer fragments than half the budget: nothing is removed and the curve is
// the exact visibility t^(fragments strictly in front).
TEST(AvsmMath, WithinTheBudgetTheCurveIsExact) {
  const std::vector<float> depths = {0.7f, 0.2f, 0.5f, 0.2f};  // arrival order, a tie at 0.2
  int removed = -1;
  const AvsmCurve c = streamed(depths, 0.5f, 8, &removed);
  EXPECT_EQ(removed, 0);
  for (float z = 0.0f; z <= 1.0f; z += 0.01f) {
    const int n = int(std::count_if(depths.begin(), depths.end(), [&](float d) { return d < z; }));
    EXPECT_FLOAT_EQ(lookup(c, z), std::pow(0.5f, float(n))) << z;
  }
}

TEST(AvsmMath, AlphaZeroAndOne) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> depths(300);
  for (float& d : depths) d = u(rng);
  const float front = *std::min_element(depths.begin(), depths.end());
  const AvsmCurve clear = streamed(depths, 1.0f, 8);
  const AvsmCurve opaque = streamed(depths, 0.0f, 8);
  for (float z = -0.1f; z <= 1.1f; z += 0.001f) {
    EXPECT_EQ(lookup(clear, z), 1.0f) << z;
    EXPECT_EQ(lookup(opaque, z), z > front ? 0.0f : 1.0f) << z;
  }
}

// Thousands of fragments, every budget: finite, in [0, 1], never rising
// along the ray, the first node at 1 and the last carrying the exact total
// transmittance (the paper never removes it).
TEST(AvsmMath, ThousandsOfFragmentsStayBoundedFallingAndExactBehind) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const int budget : {4, 8, 16}) {
    for (const int n : {1, 10, 3000}) {
      std::vector<float> depths(n);
      for (float& d : depths) d = u(rng);
      const float t = 0.97f;
      const AvsmCurve c = streamed(depths, t, budget);
      ASSERT_LE(c.count, budget);
      EXPECT_EQ(c.n[0].y, 1.0f);
      EXPECT_NEAR(c.n[c.count - 1].y, std::pow(t, float(n)), 1e-4f * std::pow(t, float(n)) + 1e-7f);
      float prev = 1.0f;
      for (float z = -0.05f; z <= 1.05f; z += 1e-4f) {
        const float v = lookup(c, z);
        ASSERT_TRUE(std::isfinite(v)) << z;
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
        ASSERT_LE(v, prev) << "rises at " << z << " (budget " << budget << ", " << n << ")";
        prev = v;
      }
    }
  }
}

// More nodes, less error against the exact visibility (averaged over texels
// of random fragments).
TEST(AvsmMath, ErrorFallsWithMoreNodes) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double err[3] = {0, 0, 0};
  for (int texel = 0; texel < 200; ++texel) {
    std::vector<float> depths(40);
    for (float& d : depths) d = u(rng);
    std::vector<float> sorted = depths;
    std::sort(sorted.begin(), sorted.end());
    int k = 0;
    for (const int budget : {4, 8, 16}) {
      const AvsmCurve c = streamed(depths, 0.8f, budget);
      for (float z = 0.0f; z < 1.0f; z += 0.01f) {
        const auto in = std::lower_bound(sorted.begin(), sorted.end(), z) - sorted.begin();
        const double e = lookup(c, z) - std::pow(0.8, double(in));
        err[k] += e * e;
      }
      ++k;
    }
  }
  std::cout << "[ measured ] avsm squared error 4/8/16 nodes: " << err[0] << " / " << err[1]
            << " / " << err[2] << "\n";
  EXPECT_GT(err[0], err[1]);
  EXPECT_GT(err[1], err[2]);
}

// --- GPU: both backends against the exact visibility ---

class ShadowAvsm : public sbtest::ProbedShadowTest {};

// The ordering: on the stray scene, AVSM with 8 nodes has a lower
// visibility RMSE than deep opacity maps with 3 layers (same map size).
TEST_P(ShadowAvsm, AvsmWith8NodesBelowDomWith3LayersOnStray) {
  const RenderResult avsm = run(request("stray:strands=1500", "avsm:nodes=8,size=128"));
  const RenderResult dom = run(request("stray:strands=1500", "dom:layers=3,size=128"));
  EXPECT_GT(avsm.visibilityError->pixels, 500u);
  EXPECT_LT(avsm.visibilityError->rmse, dom.visibilityError->rmse);
}

// The curves render within the invariants; AVSM's timing is marked emulated
// (no interlock path), its counters count the fragments streamed; the error
// falls from 4 to 16 nodes; with fewer fragments per texel than half the
// budget nothing is removed and AVSM is the exact visibility.
TEST_P(ShadowAvsm, AvsmRendersItsCurvesAndMarksTheTimingEmulated) {
  double prev = 1e9;
  for (const int nodes : {4, 16}) {
    const RenderResult out =
        run(request("curly:strands=300", "avsm:size=128,nodes=" + std::to_string(nodes)));
    EXPECT_NE(out.timingEmulated.find("avsm"), std::string::npos) << out.timingEmulated;
    EXPECT_GT(counter(out, "emulated_steps"), 0.0);
    EXPECT_LE(counter(out, "avsm_nodes_max"), double(nodes));
    if (nodes == 4) {
      EXPECT_GT(out.visibilityError->rmse, 0.0);  // 16 may be exact here
    }
    EXPECT_LT(out.visibilityError->rmse, prev) << nodes;
    prev = out.visibilityError->rmse;
  }
  const RenderResult sparse = run(request("straight:strands=6,points=8", "avsm:size=128,nodes=16"));
  ASSERT_EQ(counter(sparse, "avsm_nodes_removed"), 0.0);
  EXPECT_GT(counter(sparse, "emulated_steps"), 0.0);
  EXPECT_LE(sparse.visibilityError->max, 1e-5);
  // The same comparison fails once the budget is too small to keep the steps.
  const RenderResult cut = run(request("straight:strands=400,points=8", "avsm:size=128,nodes=4"));
  EXPECT_GT(counter(cut, "avsm_nodes_removed"), 0.0);
  EXPECT_GT(cut.visibilityError->max, 1e-5);
}

TEST_P(ShadowAvsm, BadOptionsAreRejectedNamingThem) {
  for (const auto& [shadow, name] : std::vector<std::pair<std::string, std::string>>{
           {"avsm:nodes=5", "nodes"}, {"avsm:nodes=32", "nodes"}}) {
    RenderRequest r = request("straight:strands=10", shadow);
    try {
      runRender(r);
      ADD_FAILURE() << "no error for " << shadow;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ShadowAvsm, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

TEST(ShadowAvsmInvariants, BothPromiseToFall) {
  EXPECT_TRUE(makeShadowTechnique(Spec::parse("avsm"))->monotone());
}

// GL and Vulkan render them alike (visibility within 1e-4).
TEST(ShadowAvsmParity, GlAndVulkanAgree) {
  const sbtest::BothBackends both = sbtest::makeBothBackends();
  if (!both.unavailable.empty()) GTEST_SKIP() << both.unavailable;
  sbtest::expectShadowParity(both, {"avsm:size=128,nodes=8"});
}

}  // namespace
}  // namespace sb
