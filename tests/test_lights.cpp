// Several lights (--extra-lights): the setting's forms and refusals, and on
// both backends the image of two lights against the images of each light
// alone, the per-light times and memory, and the passes an extra light adds.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "harness/measures/lights/lights.h"
#include "harness/render.h"
#include "harness/settings.h"
#include "tests/test_util.h"

namespace sb {
namespace {

const Setting& extraLights() { return *findSetting("extra_lights"); }

TEST(ExtraLightsSetting, TextAndJsonFormsMeanTheSame) {
  RenderRequest a, b;
  setFromText(a, extraLights(), "point:1,2,3:1,0.5,0.25:0.5;directional:-1,0,0");
  setFromJson(b, extraLights(),
              nlohmann::ordered_json::parse(
                  R"([{"type": "point", "position": [1, 2, 3], "color": [1, 0.5, 0.25],
                       "intensity": 0.5}, "directional:-1,0,0"])"));
  ASSERT_EQ(a.extraLights.size(), 2u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.extraLights[0].type, "point");
  EXPECT_EQ(a.extraLights[0].at, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(a.extraLights[0].intensity, 0.5f);
  EXPECT_EQ(a.extraLights[1].type, "directional");
  EXPECT_EQ(a.extraLights[1].color, glm::vec3(1));  // defaults
  EXPECT_FLOAT_EQ(a.extraLights[1].intensity, 1.0f);
  // The text form goes round: what `sweep` and manifests write reads back the same.
  RenderRequest c;
  setFromText(c, extraLights(), settingText(a, extraLights()));
  EXPECT_EQ(c, a);
}

TEST(ExtraLightsSetting, BadLightsAreRefusedByName) {
  RenderRequest r;
  sbtest::expectInputError([&] { setFromText(r, extraLights(), "spot:1,2,3"); },
                           {"--extra-lights", "unknown light type 'spot'"});
  sbtest::expectInputError([&] { setFromText(r, extraLights(), "point:1,2"); },
                           {"--extra-lights", "TYPE:X,Y,Z"});
  sbtest::expectInputError([&] { setFromText(r, extraLights(), "directional:0,0,0"); },
                           {"direction must be non-zero"});
  sbtest::expectInputError([&] { setFromText(r, extraLights(), "point:1,2,3:1,1,1:-1"); },
                           {"intensity must be >= 0"});
  std::string eight;
  for (int i = 0; i < 8; ++i) eight += (i ? ";" : "") + std::string("point:1,2,3");
  sbtest::expectInputError([&] { setFromText(r, extraLights(), eight); }, {"at most 7"});
  sbtest::expectInputError(
      [&] {
        setFromJson(
            r, extraLights(),
            nlohmann::ordered_json::parse(R"([{"type": "point", "direction": [1, 0, 0]}])"));
      },
      {"\"extra_lights\"", "needs \"position\""});
  EXPECT_TRUE(r.extraLights.empty()) << "nothing set by a refused value";
}

class ExtraLights : public ::testing::TestWithParam<const char*> {
 protected:
  RenderRequest request(const std::string& lightType, glm::vec3 at) const {
    RenderRequest r;
    r.scene = "curly:strands=150,points=16,seed=3,alpha=0.5";  // hair on a head mesh
    r.backend = GetParam();
    r.width = r.height = 48;
    r.repeat = 2;
    r.warmup = 0;
    r.shadow = "osm:size=64,maps=8";
    r.oit = "abuffer";  // exact, linear in the hair's colour
    r.view.lightType = lightType;
    if (lightType == "point")
      r.view.lightPosition = at;
    else
      r.view.lightDirection = at;
    return r;
  }
};

// Multipass lighting is exact for a technique that composites linearly: the
// image of lights 1 and 2 plus the image of an unlit scene (the ambient term
// and the background once more) is the image of light 1 alone plus that of
// light 2 alone. A second light that reused the first's shadow maps, or
// counted the ambient term or the background twice, breaks this.
TEST_P(ExtraLights, TwoLightsAreTheSumOfEachLightAlone) {
  const glm::vec3 at1(-1.0f, -1.0f, -0.5f), at2(2.5f, 1.0f, 2.0f);
  RenderRequest both = request("directional", at1);
  both.extraLights = {{"point", at2, glm::vec3(0.9f, 0.8f, 0.6f), 0.8f}};
  RenderRequest first = request("directional", at1);
  RenderRequest second = request("point", at2);
  second.view.lightColor = glm::vec3(0.9f, 0.8f, 0.6f);
  second.view.lightIntensity = 0.8f;
  RenderRequest unlit = request("directional", at1);
  unlit.view.lightIntensity = 0.0f;

  const RenderResult r12 = runRender(both), r1 = runRender(first), r2 = runRender(second),
                     r0 = runRender(unlit);
  ASSERT_EQ(r12.image.pixels.size(), r1.image.pixels.size());
  double worst = 0, added = 0;
  for (std::size_t i = 0; i < r12.image.pixels.size(); ++i) {
    if (i % 4 == 3) continue;  // alpha is 1 everywhere
    const double lhs = r12.image.pixels[i] + r0.image.pixels[i];
    const double rhs = r1.image.pixels[i] + r2.image.pixels[i];
    worst = std::max(worst, std::abs(lhs - rhs));
    added = std::max(added, double(r12.image.pixels[i] - r1.image.pixels[i]));
  }
  std::cout << "[ measured ] " << GetParam() << ": |I12 + I0 - I1 - I2| max " << worst
            << ", the second light adds up to " << added << "\n";
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(added, 0.05) << "the second light must light something";

  // Each light's share: its own shadow maps (as many bytes as the key light's)
  // and passes; the sum of the lights is a pass of its own.
  ASSERT_TRUE(r12.measure<LightShares>());
  const std::vector<LightShare>& lights = r12.measure<LightShares>()->lights;
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_GT(lights[0].shadowBytes, 0u);
  EXPECT_EQ(lights[1].shadowBytes, lights[0].shadowBytes);
  EXPECT_EQ(lights[1].light.type, LightType::Point);
  for (const auto& l : lights) {
    ASSERT_EQ(l.ms.size(), 2u);
    EXPECT_GT(l.ms[0], 0.0);
  }
  auto hasPass = [&](const std::string& name) {
    return std::any_of(r12.passes.begin(), r12.passes.end(),
                       [&](const PassTimes& p) { return p.name == name; });
  };
  EXPECT_TRUE(hasPass("lights.sum"));
  EXPECT_TRUE(hasPass("osm.map"));
  EXPECT_TRUE(hasPass("light2.osm.map"));
  EXPECT_FALSE(r1.measure<LightShares>()) << "one light: no per-light block";
  const nlohmann::json j = renderJson(r12);
  ASSERT_TRUE(j.contains("lights"));
  EXPECT_EQ(j["lights"][1]["prefix"], "light2.");
  EXPECT_EQ(j["lights"][1]["type"], "point");
}

// The visibility output and its error stay the key light's: a second light
// changes neither.
TEST_P(ExtraLights, VisibilityIsTheKeyLights) {
  RenderRequest one = request("directional", glm::vec3(-1.0f, -1.0f, -0.5f));
  one.reference = true;
  one.image = false;
  one.repeat = 1;
  RenderRequest two = one;
  two.extraLights = {{"directional", glm::vec3(1.0f, -0.2f, 0.0f), glm::vec3(1.0f), 1.0f}};
  const RenderResult a = runRender(one), b = runRender(two);
  EXPECT_EQ(a.visibility, b.visibility);
  EXPECT_EQ(a.visibilityError->rmse, b.visibilityError->rmse);
  // A visibility-only frame draws nothing of the second light.
  for (const std::string& p : b.graph) EXPECT_EQ(p.rfind("light2.", 0), std::string::npos) << p;
}

INSTANTIATE_TEST_SUITE_P(Backends, ExtraLights, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace sb
