// Helpers for tests that render in-process on both backends.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "backends/device.h"
#include "harness/measures/invariants/invariants.h"
#include "harness/measures/probe/probe.h"
#include "harness/render.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "render/common/technique.h"
#include "scenes/view.h"
#include "tests/test_util.h"

namespace sbtest {

// A device with Vulkan validation on (GL: EGL surfaceless; Vulkan: headless).
inline std::unique_ptr<sb::Device> makeDevice(const std::string& backend) {
  sb::DeviceOptions o;
  o.backend = backend;
  o.platform = backend == "gl" ? "egl" : "headless";
  o.validation = true;
  return sb::createDevice(o);
}

// GL and Vulkan devices together, for tests that compare the two; `unavailable`
// says why not when either cannot be created here.
struct BothBackends {
  std::unique_ptr<sb::Device> gl, vk;
  std::string unavailable;
};
inline BothBackends makeBothBackends() {
  BothBackends b;
  try {
    b.gl = makeDevice("gl");
    b.vk = makeDevice("vulkan");
  } catch (const sb::DeviceError& e) {
    b.unavailable = std::string("backend unavailable: ") + e.what();
  }
  return b;
}

// A test run once per backend name; a backend that cannot be created here is
// skipped with the reason, and any Vulkan validation message fails the test.
class BackendTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    try {
      dev_ = makeDevice(GetParam());
    } catch (const sb::DeviceError& e) {
      GTEST_SKIP() << "backend unavailable: " << e.what();
    }
    messages_ = sb::validationMessageCount();
  }
  void TearDown() override {
    if (dev_) {
      EXPECT_EQ(sb::validationMessageCount(), messages_) << "Vulkan validation messages";
    }
  }
  std::unique_ptr<sb::Device> dev_;
  std::size_t messages_ = 0;
};

// A shadow technique against the exact reference on one backend: 96x96, invariants on, and
// the light ray through texel (64, 64) of a 128x128 map probed at 256 depths.
class ProbedShadowTest : public BackendTest {
 protected:
  sb::RenderRequest request(const std::string& scene, const std::string& shadow) {
    sb::RenderRequest r;
    r.scene = scene;
    r.shadow = shadow;
    r.backend = GetParam();
    r.width = r.height = 96;
    r.repeat = 1;
    r.warmup = 0;
    r.reference = true;
    r.invariants = true;
    sb::ProbeSpec p;
    p.mapSize = 128;
    p.texel = {64, 64};
    p.samples = 256;
    r.probe = p;
    return r;
  }
  // Largest |technique - exact| along the probe ray.
  static double probeMaxError(const sb::RenderResult& out) {
    double worst = 0;
    const sb::ProbeResult& probe = *out.measure<sb::ProbeResult>();
    for (std::size_t i = 0; i < probe.exact.size(); ++i)
      worst = std::max(worst, double(std::abs(probe.visibility[i] - probe.exact[i])));
    return worst;
  }
  static double counter(const sb::RenderResult& out, const std::string& name) {
    for (const sb::Counter& c : out.counters)
      if (c.name == name) return c.value;
    ADD_FAILURE() << "no counter " << name;
    return 0;
  }
  // Renders r, prints its visibility errors and expects its invariants to hold.
  sb::RenderResult run(const sb::RenderRequest& r) {
    sb::RenderResult out = sb::runRender(r);
    std::cout << "[ measured ] " << r.backend << " " << r.scene << " " << r.shadow
              << ": visibility RMSE " << out.visibilityError->rmse << ", max "
              << out.visibilityError->max << ", probe max " << probeMaxError(out) << "\n";
    const auto& failures = out.measure<sb::InvariantsResult>()->failures;
    EXPECT_TRUE(failures.empty()) << failures.front().what;
    return out;
  }
};

inline std::vector<float> floats(const std::vector<uint8_t>& bytes) {
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
  return v;
}

// Renders each shadow technique on curly hair (300 strands, 96x96, with the
// exact reference) on GL and on Vulkan, prints their visibility's max
// difference and expects it within `tolerance`.
inline void expectShadowParity(const BothBackends& both, std::initializer_list<std::string> shadows,
                               double tolerance = 1e-4) {
  for (const std::string& shadow : shadows) {
    sb::RenderRequest r;
    r.scene = "curly:strands=300";
    r.shadow = shadow;
    r.width = r.height = 96;
    r.warmup = 0;
    r.reference = true;
    r.backend = "gl";
    const sb::RenderResult gl = sb::runRender(r, nullptr, both.gl.get());
    r.backend = "vulkan";
    const sb::RenderResult vk = sb::runRender(r, nullptr, both.vk.get());
    const sb::VisibilityError d =
        sb::compareVisibility(floats(gl.visibility), floats(vk.visibility));
    std::cout << "[ measured ] " << shadow << ": GL vs Vulkan visibility max " << d.max << "\n";
    EXPECT_LE(d.max, tolerance) << shadow;
  }
}

// Square image, camera and directional light fitted to the scene.
inline sb::RenderSettings fittedSettings(const sb::Scene& scene, uint32_t size) {
  sb::RenderSettings s;
  s.width = s.height = size;
  s.camera = sb::fitCamera(scene.bounds(), 1.0f);
  s.light = sb::fitLight(scene.bounds(), sb::LightType::Directional);
  return s;
}

// `strandbench render <args> --json --out <a temporary .exr>`, for a run on
// a driver of its own (--driver: one per process): its exit status, stderr,
// JSON and float image (when it rendered), and whether it wrote the image.
struct CliRender {
  int status = -1;
  std::string err;
  nlohmann::json json;
  sb::Image image;
  bool wrote = false;
};
inline CliRender renderCli(const std::string& args) {
  const auto dir = tempDir("cli-render");
  const std::string exr = (dir / "image.exr").string();
  const CliResult r = runCli("render " + args + " --json --out " + exr);
  CliRender c{r.status, r.err, {}, {}, std::filesystem::exists(exr)};
  if (r.status == 0) {
    c.json = nlohmann::json::parse(r.out.substr(r.out.find('{')));
    c.image = sb::readImage(exr);
  }
  std::filesystem::remove_all(dir);
  return c;
}

// A counter of a render's JSON, or -1 when it has none of that name.
inline double jsonCounter(const nlohmann::json& j, const std::string& name) {
  return j.contains("counters") && j["counters"].contains(name) ? j["counters"][name].get<double>()
                                                                : -1.0;
}

// Both tiers of a ray-traced technique (`render(tier)`: with tier=<tier> on
// Mesa 25.0.7's Vulkan, which offers ray queries), each checked to have run
// in its tier: the JSON's tier, and `tierCounter` 1 for ray queries, else 0.
struct BothTiers {
  CliRender software, rayQuery;
  bool rendered() const { return software.status == 0 && rayQuery.status == 0; }
};
inline BothTiers renderBothTiers(const std::function<CliRender(const std::string& tier)>& render,
                                 const std::string& tierCounter) {
  BothTiers b{render("software"), render("ray_query")};
  for (const CliRender* r : {&b.software, &b.rayQuery}) {
    const bool rq = r == &b.rayQuery;
    EXPECT_EQ(r->status, 0) << r->err;
    if (r->status != 0) continue;
    EXPECT_EQ(r->json["tier"], rq ? "ray_query" : "software");
    EXPECT_EQ(jsonCounter(r->json, tierCounter), rq ? 1.0 : 0.0);
  }
  return b;
}

// The tiers of a ray-traced technique (--shadow rt, --oit rt) on the drivers
// here: `render(driver, backend, tier)` renders it with tier=<tier>. tier=auto
// is the faster tier: the software tier on every device here, Mesa 25.0.7's
// Vulkan included, which offers VK_KHR_ray_query but is a CPU device (its ray
// queries run in shader code, far slower); and the JSON's tier_reason says
// why. Ray queries on a GPU are the rule's other side (suites/ray-tracing.json).
using TierRender = std::function<CliRender(const std::string& driver, const std::string& backend,
                                           const std::string& tier)>;
inline void expectAutoPicksTheFasterTier(const TierRender& render) {
  for (const auto& [driver, backend, why] :
       {std::tuple{"mesa-25.0", "vulkan", "a CPU device"},
        std::tuple{"mesa-25.0", "gl", "the device offers no VK_KHR_ray_query"},
        std::tuple{"system", "vulkan", "the device offers no VK_KHR_ray_query"},
        std::tuple{"system", "gl", "the device offers no VK_KHR_ray_query"}}) {
    const CliRender r = render(driver, backend, "auto");
    ASSERT_EQ(r.status, 0) << driver << " " << backend << ": " << r.err;
    EXPECT_EQ(r.json["tier"], "software") << driver << " " << backend;
    const std::string reason = r.json.value("tier_reason", "");
    EXPECT_NE(reason.find(std::string("auto: ") + why), std::string::npos)
        << driver << " " << backend << ": " << reason;
  }
  // The control: asked for, the ray-query tier runs there and says so.
  const CliRender rq = render("mesa-25.0", "vulkan", "ray_query");
  ASSERT_EQ(rq.status, 0) << rq.err;
  EXPECT_EQ(rq.json["tier"], "ray_query");
  EXPECT_EQ(rq.json["tier_reason"], "tier=ray_query asked for");
}
// tier=ray_query where the device has no ray queries (the system's Mesa 22.3,
// GL anywhere): exit status 2, the reason naming `technique` ("shadow
// technique 'rt'"), nothing written.
inline void expectRayQueryRefusedWhereNotOffered(const TierRender& render,
                                                 const std::string& technique) {
  for (const auto& [driver, backend] :
       {std::pair{"system", "vulkan"}, std::pair{"system", "gl"}, std::pair{"mesa-25.0", "gl"}}) {
    const CliRender r = render(driver, backend, "ray_query");
    EXPECT_EQ(r.status, 2) << driver << " " << backend << ": " << r.err;
    EXPECT_NE(r.err.find(technique + ": tier=ray_query: this device"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("offers no VK_KHR_ray_query"), std::string::npos) << r.err;
    EXPECT_TRUE(r.json.is_null());
    EXPECT_FALSE(r.wrote);
  }
}

}  // namespace sbtest
