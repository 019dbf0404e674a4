// Ray-traced strand shadows (--shadow rt, software and ray-query tiers).
// On the CPU: the BVH (techniques/rt/bvh.h) and the ray-segment test shared
// with the GLSL (techniques/rt/rt_math.glsl). On both backends: GL and Vulkan
// agree; with one ray per point and no cap rt matches the exact reference on a
// tie-free scene of wide ribbons; its error against the anti-aliased reference
// falls as rays per point rise. On Mesa 25.0.7's lavapipe (drivers/mesa-25.0,
// through the CLI: one process, one driver): the ray-query tier renders and
// agrees with the software tier, and tier=auto picks the software tier there (a
// CPU device, where ray queries are far slower), with progress lines when
// stdout and stderr are files; elsewhere tier=ray_query is bad input. Each
// comparison also shows it can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "gpu_test_util.h"
#include "harness/render.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "techniques/rt/bvh.h"
#include "tests/test_util.h"

namespace sb {
namespace {

using glm::vec3;

// --- the ray-segment test (rt_math.glsl) by hand ---

TEST(RtMath, ARayAcrossASegmentHitsWithinTheRadiusOnly) {
  // Segment along x from (-1,0,0) to (1,0,0); rays along +z from z = -2.
  const vec3 a(-1, 0, 0), b(1, 0, 0), d(0, 0, 1);
  glm::vec4 h = glsl::rtSegmentHit(vec3(0.25f, 0.05f, -2), d, a, b, 0.1f);
  EXPECT_EQ(h.x, 1.0f);
  EXPECT_NEAR(h.y, 2.0f, 1e-6);     // t at the closest approach: the axis' depth
  EXPECT_NEAR(h.z, 0.625f, 1e-6);   // s along the segment
  EXPECT_NEAR(h.w, 0.0025f, 1e-6);  // squared distance 0.05^2
  EXPECT_EQ(glsl::rtSegmentHit(vec3(0.25f, 0.15f, -2), d, a, b, 0.1f).x, 0.0f);  // beyond r
  EXPECT_EQ(glsl::rtSegmentHit(vec3(1.05f, 0.0f, -2), d, a, b, 0.1f).x, 0.0f);   // past the end
  // A ray along the segment (seen end-on) is no hit.
  EXPECT_EQ(glsl::rtSegmentHit(vec3(-2, 0, 0), vec3(1, 0, 0), a, b, 0.1f).x, 0.0f);
  // An oblique ray: still the closest approach of the two lines.
  const vec3 od = glm::normalize(vec3(0, 1, 1));
  h = glsl::rtSegmentHit(vec3(0.5f, -2, -2), od, a, b, 0.1f);
  EXPECT_EQ(h.x, 1.0f);
  EXPECT_NEAR(h.y, std::sqrt(8.0f), 1e-5);
  EXPECT_NEAR(h.z, 0.75f, 1e-6);
}

TEST(RtMath, AJointBetweenTwoSegmentsOfAStrandCountsOnce) {
  // Consecutive segments meet at (0,0,0); a ray through the joint crosses the
  // strand once (capsules would count it twice: their caps overlap there).
  const vec3 p0(-1, 0, 0), p1(0, 0, 0), p2(1, 0.2f, 0), d(0, 0, 1);
  for (const float x : {-1e-3f, 0.0f, 1e-3f}) {
    const vec3 o(x, 0, -2);
    const float hits =
        glsl::rtSegmentHit(o, d, p0, p1, 0.1f).x + glsl::rtSegmentHit(o, d, p1, p2, 0.1f).x;
    EXPECT_EQ(hits, 1.0f) << x;
  }
}

TEST(RtMath, BoxTestAndJitter) {
  const vec3 inv = glsl::rtSafeInverse(vec3(0, 0, 1));
  EXPECT_TRUE(glsl::rtBoxHit(vec3(0, 0, -2), inv, vec3(-1), vec3(1), 10.0f));
  EXPECT_FALSE(glsl::rtBoxHit(vec3(0, 0, -2), inv, vec3(-1), vec3(1), 0.5f));  // past tMax
  EXPECT_FALSE(glsl::rtBoxHit(vec3(2, 0, -2), inv, vec3(-1), vec3(1), 10.0f));
  EXPECT_FALSE(glsl::rtBoxHit(vec3(0, 0, 2), inv, vec3(-1), vec3(1), 10.0f));  // behind
  // One ray is the point itself; more stay inside the texel and average to its centre.
  EXPECT_EQ(glsl::rtJitter(0, 1), glm::vec2(0.0f));
  glm::vec2 sum(0.0f);
  for (int k = 0; k < 16; ++k) {
    const glm::vec2 j = glsl::rtJitter(k, 16);
    EXPECT_LE(glm::max(std::abs(j.x), std::abs(j.y)), 0.5f);
    sum += j;
  }
  EXPECT_LT(glm::length(sum / 16.0f), 0.05f);
}

// --- the BVH on random segments ---

std::vector<rt::Segment> randomSegments(uint32_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), r(0.001f, 0.05f);
  std::vector<rt::Segment> segs(n);
  for (rt::Segment& s : segs) {
    s.a = vec3(u(rng), u(rng), u(rng));
    s.b = s.a + 0.1f * vec3(u(rng), u(rng), u(rng));
    s.radius = r(rng);
  }
  return segs;
}

bool contains(const rt::Node& outer, vec3 lo, vec3 hi) {
  return glm::all(glm::lessThanEqual(outer.lo, lo)) &&
         glm::all(glm::greaterThanEqual(outer.hi, hi));
}

TEST(RtBvh, EverySegmentIsReachableOnceAndBoundsContainTheirChildren) {
  for (const bool sah : {true, false})
    for (const uint32_t n : {0u, 1u, 5u, 1000u}) {
      SCOPED_TRACE(sah ? "sah" : "median");
      const std::vector<rt::Segment> segs = randomSegments(n, 7 + n);
      const rt::Bvh bvh = rt::buildBvh(segs, 4, sah);
      if (n == 0) {  // one leaf of one zero-length segment (a buffer may not be empty)
        ASSERT_EQ(bvh.nodes.size(), 1u);
        EXPECT_EQ(bvh.nodes[0].count, 1u);
        EXPECT_EQ(rt::packSegments(bvh, segs), std::vector<glm::vec4>(2, glm::vec4(0.0f)));
        EXPECT_EQ(glsl::rtSegmentHit(vec3(0, 0, -1), vec3(0, 0, 1), vec3(0), vec3(0), 0.0f).x,
                  0.0f);
        EXPECT_EQ(rt::countHits(bvh, segs, vec3(0), vec3(0, 0, 1), 0.0f, 1e30f), 0u);
        continue;
      }
      std::multiset<uint32_t> reached;
      std::vector<uint32_t> stack{0};
      uint32_t visited = 0;
      while (!stack.empty()) {
        const uint32_t i = stack.back();
        stack.pop_back();
        ASSERT_LT(i, bvh.nodes.size());
        ++visited;
        const rt::Node& node = bvh.nodes[i];
        if (node.count == 0) {
          ASSERT_LT(node.leftOrFirst, bvh.nodes.size());
          for (const uint32_t c : {i + 1, node.leftOrFirst}) {
            EXPECT_TRUE(contains(node, bvh.nodes[c].lo, bvh.nodes[c].hi)) << "node " << i;
            stack.push_back(c);
          }
          continue;
        }
        for (uint32_t k = node.leftOrFirst; k < node.leftOrFirst + node.count; ++k) {
          vec3 lo, hi;
          rt::segmentBounds(segs[bvh.order[k]], lo, hi);
          EXPECT_TRUE(contains(node, lo, hi)) << "leaf " << i;
          reached.insert(bvh.order[k]);
        }
      }
      EXPECT_EQ(visited, bvh.nodes.size()) << n;  // no node unreachable
      EXPECT_EQ(reached.size(), n);
      for (uint32_t s = 0; s < n; ++s) EXPECT_EQ(reached.count(s), 1u) << s;
      // The shader's stack (48) is far from full: median splits are balanced,
      // SAH ones turn to the median below rt::kSahLevels.
      if (n) {
        const uint32_t balanced = 2 + uint32_t(std::ceil(std::log2(double(n))));
        EXPECT_LE(bvh.depth, sah ? rt::kSahLevels + balanced : balanced);
      }
    }
}

TEST(RtBvh, TraversalFindsWhatBruteForceFinds) {
  const std::vector<rt::Segment> segs = randomSegments(2000, 3);
  const rt::Bvh bvh = rt::buildBvh(segs), median = rt::buildBvh(segs, 4, false);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  uint64_t total = 0;
  for (int i = 0; i < 500; ++i) {
    const vec3 o(u(rng), u(rng), u(rng));
    const vec3 d = glm::normalize(vec3(u(rng), u(rng), u(rng)) + vec3(0, 0, 0.01f));
    uint32_t brute = 0;
    for (const rt::Segment& s : segs) {
      const glm::vec4 h = glsl::rtSegmentHit(o, d, s.a, s.b, s.radius);
      if (h.x > 0.0f && h.y > 0.0f && h.y < 5.0f) ++brute;
    }
    EXPECT_EQ(rt::countHits(bvh, segs, o, d, 0.0f, 5.0f), brute) << i;
    EXPECT_EQ(rt::countHits(median, segs, o, d, 0.0f, 5.0f), brute) << i;
    total += brute;
  }
  EXPECT_GT(total, 200u);  // the rays do cross segments
  // Can fail: a BVH whose root box misses the segments finds nothing.
  rt::Bvh broken = bvh;
  broken.nodes[0].hi = broken.nodes[0].lo;
  uint64_t found = 0;
  std::mt19937 again(11);
  for (int i = 0; i < 500; ++i) {
    const vec3 o(u(again), u(again), u(again));
    const vec3 d = glm::normalize(vec3(u(again), u(again), u(again)) + vec3(0, 0, 0.01f));
    found += rt::countHits(broken, segs, o, d, 0.0f, 5.0f);
  }
  EXPECT_LT(found, total);
}

// --- on the GPU ---

RenderRequest rtRequest(const std::string& backend, const std::string& scene,
                        const std::string& shadow, uint32_t size) {
  RenderRequest r;
  r.scene = scene;
  r.shadow = shadow;
  r.backend = backend;
  r.width = r.height = size;
  r.warmup = 0;
  r.repeat = 1;
  r.reference = true;
  return r;
}

double counter(const RenderResult& out, const std::string& name) {
  for (const Counter& c : out.counters)
    if (c.name == name) return c.value;
  ADD_FAILURE() << "no counter " << name;
  return -1;
}

// GL and Vulkan: the same visibility within 1e-4 (curly:strands=300, 96x96),
// directional and capped rays; the BVH counters are reported alike.
TEST(RtShadowParity, GlAndVulkanAgree) {
  const sbtest::BothBackends both = sbtest::makeBothBackends();
  if (!both.unavailable.empty()) GTEST_SKIP() << both.unavailable;
  sbtest::expectShadowParity(both, {"rt:size=128", "rt:size=128,rays=4,max_hits=2"});
  RenderRequest r = rtRequest("gl", "curly:strands=300", "rt:size=128,max_hits=2", 96);
  r.view.lightType = "point";
  const RenderResult gl = runRender(r, nullptr, both.gl.get());
  r.backend = "vulkan";
  const RenderResult vk = runRender(r, nullptr, both.vk.get());
  const VisibilityError d =
      compareVisibility(sbtest::floats(gl.visibility), sbtest::floats(vk.visibility));
  std::cout << "[ measured ] rt point light: GL vs Vulkan visibility max " << d.max << "\n";
  EXPECT_LE(d.max, 1e-4);
  EXPECT_GT(counter(gl, "rt.max_hits_reached"), 0.0);  // the cap is reached, and counted
  EXPECT_EQ(counter(gl, "rt.max_hits_reached"), counter(vk, "rt.max_hits_reached"));
  EXPECT_EQ(counter(gl, "rt.bvh_nodes"), counter(vk, "rt.bvh_nodes"));
  EXPECT_EQ(counter(gl, "rt.segments"), 300.0 * 47);  // curly: 48 points per strand
}

class RtShadow : public sbtest::BackendTest {};

// Wide ribbons (10 light texels, 128 map, 128x128 image), few strands, so no
// two fragments tie; bias 0.05 for both, so that neither shadows a strand by
// itself (the exact map's one-texel depth quantization otherwise stripes
// the ribbons: acne that rays at the point itself do not have). What is left
// are shadow edges: exact takes the texel's centre, a ray the point itself.
// Tolerance: at most 3% of the hair pixels off by more than 0.01 (measured
// 2.4%, 53 of 2255, on both APIs), visibility RMSE <= 0.1 (measured 0.073:
// the few edge pixels are off by up to 0.75).
TEST_P(RtShadow, OneRayNoCapMatchesTheExactReferenceOnWideRibbons) {
  const std::string scene = "straight:strands=8,points=4,seed=5,head=0";
  auto visibility = [&](const std::string& sceneSpec, const std::string& shadow) {
    RenderRequest r = rtRequest(GetParam(), sceneSpec, shadow, 128);
    r.primitive = "ribbons";
    r.ribbonWidth = 10.0f;
    r.image = false;
    return sbtest::floats(runRender(r, nullptr, dev_.get()).visibility);
  };
  auto offPixels = [](const std::vector<float>& a, const std::vector<float>& b) {
    std::size_t hair = 0, off = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (b[i] < 0.0f) continue;  // no surface
      ++hair;
      if (std::abs(a[i] - b[i]) > 0.01f) ++off;
    }
    return std::pair{off, hair};
  };
  const std::vector<float> exact = visibility(scene, "exact:size=128,bias=0.05");
  const std::vector<float> rt = visibility(scene, "rt:size=128,bias=0.05");
  const VisibilityError e = compareVisibility(rt, exact);
  const auto [off, hair] = offPixels(rt, exact);
  std::cout << "[ measured ] " << GetParam() << " rt vs exact on wide ribbons: visibility RMSE "
            << e.rmse << ", max " << e.max << ", " << off << " of " << hair
            << " pixels off by > 0.01\n";
  EXPECT_GT(e.pixels, 300u);
  EXPECT_LE(e.rmse, 0.1);
  EXPECT_LE(double(off), 0.03 * double(hair));
  // The shadows are there: exact is below 1 on a good part of the hair.
  EXPECT_GT(std::count_if(exact.begin(), exact.end(), [](float v) { return v >= 0 && v < 0.9f; }),
            50);
  // Can fail: a wrong opacity (shadow_alpha 0.3 for rt, 0.5 for exact), or a
  // cap of one strand per ray, is far outside the tolerance.
  const std::vector<float> wrongAlpha =
      visibility(scene + ",shadow_alpha=0.3", "rt:size=128,bias=0.05");
  const std::vector<float> capped = visibility(scene, "rt:size=128,bias=0.05,max_hits=1");
  const auto [offAlpha, hairAlpha] = offPixels(wrongAlpha, exact);
  const auto [offCapped, hairCapped] = offPixels(capped, exact);
  std::cout << "[ measured ] wrong alpha: RMSE " << compareVisibility(wrongAlpha, exact).rmse
            << ", " << offAlpha << " pixels off; max_hits=1: RMSE "
            << compareVisibility(capped, exact).rmse << ", " << offCapped << " pixels off\n";
  EXPECT_GT(double(offAlpha), 0.03 * double(hairAlpha));
  EXPECT_GT(double(offCapped), 0.03 * double(hairCapped));
}

// The image error against the anti-aliased reference (aa:samples=4) falls from
// 1 to 16 rays per point (curly:strands=60, 64x64, light map 64): rays spread
// over the light texel resolve shadow edges within it, as the aa reference's
// map, 4 times as fine, does. Can fail: 16 rays with a wrong opacity
// (shadow_alpha 0.2 for 0.5) are further from it than one with the right one
// (a darker wrong opacity, 0.9, hardly moves this image error: 0.0359 against
// 0.0353, its shadowed pixels being dark in both).
// Each run on a device of its own: the aa reference makes a second device
// in-process, after which the test's GL context is no longer current.
TEST_P(RtShadow, ErrorAgainstTheAntiAliasedReferenceFallsAsRaysRise) {
  auto run = [&](const std::string& scene, int rays) {
    RenderRequest r = rtRequest(GetParam(), scene, "rt:size=64,rays=" + std::to_string(rays), 64);
    r.references = {"aa:samples=4"};
    return runRender(r);
  };
  const std::string scene = "curly:strands=60,seed=3,head=0";
  const RenderResult one = run(scene, 1), sixteen = run(scene, 16);
  ASSERT_EQ(one.moreReferences.size(), 1u);
  const double e1 = one.moreReferences[0].image.rmse, e16 = sixteen.moreReferences[0].image.rmse;
  const RenderResult wrong = run(scene + ",shadow_alpha=0.2", 16);
  const double eWrong = compareImages(wrong.image, one.moreReferences[0].referenceImage).rmse;
  std::cout << "[ measured ] " << GetParam() << " rt vs aa:samples=4 image RMSE: rays=1 " << e1
            << ", rays=16 " << e16 << ", rays=16 with shadow_alpha 0.2 " << eWrong << "\n";
  EXPECT_LT(e16, 0.95 * e1);
  EXPECT_GT(eWrong, e1);
}

// tier=ray_query is refused before anything renders on the system's Mesa
// (exit status 2 at the CLI); tier=auto there is the software tier.
TEST_P(RtShadow, RayQueryTierIsRefusedWithTheReason) {
  RenderRequest r = rtRequest(GetParam(), "curly:strands=10", "rt:tier=ray_query", 32);
  try {
    runRender(r, nullptr, dev_.get());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ray_query"), std::string::npos) << e.what();
  }
  r.shadow = "rt:tier=auto";
  RenderResult out;
  EXPECT_NO_THROW(out = runRender(r, nullptr, dev_.get()));
  EXPECT_EQ(out.tier, "software");
}

INSTANTIATE_TEST_SUITE_P(Backends, RtShadow, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// --- the two tiers, through the CLI (a driver per process) ---

constexpr const char* kTierScene = "--scene curly:strands=60,seed=3 --size 96x96 --repeat 1";

// `render` of kTierScene with rt:size=128,<shadow> on a driver and backend.
sbtest::CliRender renderTier(const std::string& driver, const std::string& backend,
                             const std::string& shadow, const std::string& scene = kTierScene) {
  return sbtest::renderCli(scene + " --driver " + driver + " --backend " + backend +
                           " --shadow rt:size=128," + shadow);
}

using sbtest::jsonCounter;

// A tiny scene in tier=<tier>, for the choice of tier.
sbtest::CliRender tinyTier(const std::string& driver, const std::string& backend,
                           const std::string& tier) {
  return renderTier(driver, backend, "tier=" + tier,
                    "--scene curly:strands=10 --size 32x32 --repeat 1");
}

// Both tiers on Mesa 25.0.7's lavapipe, one and four rays per point, give the
// same image within 2 8-bit codes at any pixel and RMSE <= 0.002: the rule for a
// crossing is the same code (rays.glsl); what may differ is float rounding (the
// ray query hands the shader the same ray, but the box test that finds a
// candidate is the driver's, in its own order and arithmetic; a box that
// touches the ray only within rounding may be found by one tier and not the
// other, and the segment test then decides alike). Can fail: the ray-query
// tier with shadow_alpha 0.3 (for 0.5) is far outside it. The ray-query tier's
// acceleration structure is counted among the shadow's memory.
TEST(RtTiers, BothTiersAgreeOnMesa25) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  for (const std::string rays : {"rays=1", "rays=4,max_hits=3"}) {
    SCOPED_TRACE(rays);
    const sbtest::BothTiers both = sbtest::renderBothTiers(
        [&](const std::string& tier) {
          return renderTier("mesa-25.0", "vulkan", rays + ",tier=" + tier);
        },
        "rt.tier_ray_query");
    ASSERT_TRUE(both.rendered());
    const sbtest::CliRender &sw = both.software, &rq = both.rayQuery;
    const ImageError e = compareImages(sw.image, rq.image);
    std::cout << "[ measured ] mesa-25.0 vulkan rt " << rays << ": software vs ray_query image max "
              << e.maxAbs << ", RMSE " << e.rmse << ", pixels over one code " << e.pixelsOver
              << "\n";
    EXPECT_LE(e.maxAbs, 2.0 / 255.0 + 1e-6);
    EXPECT_LE(e.rmse, 0.002);
    if (rays != "rays=1") {  // the cap counts alike
      EXPECT_GT(jsonCounter(sw.json, "rt.max_hits_reached"), 0.0);
      EXPECT_NEAR(jsonCounter(rq.json, "rt.max_hits_reached"),
                  jsonCounter(sw.json, "rt.max_hits_reached"),
                  0.01 * jsonCounter(sw.json, "rt.max_hits_reached") + 2.0);
      continue;
    }
    // The acceleration structure, in the shadow's memory; no BVH of ours.
    bool counted = false;
    for (const auto& res : rq.json["memory"]["resources"]) {
      EXPECT_NE(res["name"], "rt.bvh_nodes");
      if (res["name"] == "rt.acceleration_structure") {
        counted = true;
        EXPECT_EQ(res["owner"], "shadow");
        EXPECT_GT(res["bytes"].get<double>(), 60.0 * 47 * 24);  // more than its boxes
      }
    }
    EXPECT_TRUE(counted) << rq.json["memory"].dump();
    // Can fail: a wrong opacity is far outside the tolerance.
    const sbtest::CliRender wrong =
        renderTier("mesa-25.0", "vulkan", rays + ",tier=ray_query",
                   "--scene curly:strands=60,seed=3,shadow_alpha=0.3 --size 96x96 --repeat 1");
    ASSERT_EQ(wrong.status, 0) << wrong.err;
    const ImageError w = compareImages(sw.image, wrong.image);
    std::cout << "[ measured ] control (ray_query, shadow_alpha 0.3): max " << w.maxAbs << ", RMSE "
              << w.rmse << "\n";
    EXPECT_GT(w.maxAbs, 2.0 / 255.0 + 1e-6);
    EXPECT_GT(w.rmse, 0.002);
  }
}

// tier=auto: the software tier on every device here: Mesa 25.0.7's Vulkan offers
// ray queries but is a CPU device (far slower there), its GL and the system's Mesa
// 22.3 have none; tier_reason says which. tier=ray_query still runs them there.
TEST(RtTiers, AutoPicksTheFasterTierAndSaysWhy) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  sbtest::expectAutoPicksTheFasterTier(tinyTier);
}

// Both ray-traced techniques with tier=auto, stdout and stderr redirected to
// files (as a batch job's): the software tier runs, and stderr gets plain
// progress lines (no carriage returns), "pass N/M" only where M is the pass
// count of the frame before (no "pass 744/6" while the reference peels), while
// stdout stays one JSON object. SB_PROGRESS_SECONDS=0 prints every update of
// this small run; the control, an interval longer than the run, prints none.
// On the system's driver too, so that the progress lines are tested without
// drivers/.
TEST(RtTiers, AutoRunsTheFasterTierAndShowsProgressOffATerminal) {
  std::vector<std::string> drivers{"system"};
  if (sbtest::mesa25Missing().empty()) drivers.push_back("mesa-25.0");
  const std::string render =
      "render --backend vulkan --scene curly:strands=10 --size 32x32 --warmup 1 --repeat 2 "
      "--shadow rt:size=32 --oit rt --reference --json --driver ";
  for (const std::string& driver : drivers) {
    SCOPED_TRACE(driver);
    const sbtest::CliResult r = sbtest::runCli(render + driver, "SB_PROGRESS_SECONDS=0");
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);  // stdout: the JSON alone
    EXPECT_EQ(j["tier"], "software");
    EXPECT_NE(j.value("tier_reason", "").find("auto: "), std::string::npos) << j.dump();
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << "a terminal's line off a terminal";
    int lines = 0;
    bool timedFrame = false, reference = false;
    std::istringstream in(r.err);
    for (std::string l; std::getline(in, l);) {
      if (!l.starts_with("render: ")) continue;
      ++lines;
      timedFrame |= l.find("render: frame 2/2, pass ") != std::string::npos;
      reference |= l.starts_with("render: reference, pass ");
      static const std::regex count(R"(pass (\d+)/(\d+))");
      std::smatch m;
      if (std::regex_search(l, m, count)) {
        EXPECT_LE(std::stoi(m[1]), std::stoi(m[2])) << l;
      }
      if (l.starts_with("render: reference")) {
        EXPECT_FALSE(std::regex_search(l, m, count)) << l;
      }
    }
    EXPECT_GT(lines, 5) << r.err;
    EXPECT_TRUE(timedFrame) << r.err;
    EXPECT_TRUE(reference) << r.err;
    const sbtest::CliResult quiet = sbtest::runCli(render + driver, "SB_PROGRESS_SECONDS=1000");
    ASSERT_EQ(quiet.status, 0) << quiet.err;
    EXPECT_EQ(quiet.err.find("render: "), std::string::npos) << quiet.err;
  }
}

// tier=ray_query where the device has no ray queries (the system's Mesa 22.3,
// GL anywhere): exit status 2, the reason, nothing written.
TEST(RtTiers, RayQueryTierWithoutRayQueriesIsBadInput) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  sbtest::expectRayQueryRefusedWhereNotOffered(tinyTier, "shadow technique 'rt'");
}

}  // namespace
}  // namespace sb
