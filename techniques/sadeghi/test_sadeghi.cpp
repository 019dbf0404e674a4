// sadeghi's own tests (picked up by the build from its folder, as techniques/*/test_*.cpp):
// its glints and its defaults, the thesis's (sadeghi.glsl compiled as C++).
#include <gtest/gtest.h>

#include <cmath>

#include "render/shading/shading_model.h"
#include "techniques/sadeghi/sadeghi.h"
#include "tests/shading_test_util.h"

namespace {

using namespace sbtest;  // kPi, kTangent, kBrown, dir

sb::ShadingModel model(const std::string& spec) { return sb::ShadingModel::fromSpec(spec); }
sb::SadeghiParams params(const std::string& spec) {
  return model(spec).paramsAs<sb::SadeghiParams>();
}
glm::vec3 sadeghi(const sb::ShadingModel& m, glm::vec3 L, glm::vec3 V, glm::vec3 c = kBrown) {
  return sb::sadeghiSpecular(m.paramsAs<sb::SadeghiParams>(), kTangent, L, V, c);
}

// Sadeghi's TRT carries the glints: I_g g'(xi_g; G_angle - phi) adds a peak at the glint angle.
TEST(SadeghiShading, SadeghiGlintsPeakAtTheGlintAngle) {
  const sb::ShadingModel m = model("sadeghi:i_r=0,i_tt=0,glint=4,glint_angle=40,glint_width=3");
  const sb::ShadingModel off = model("sadeghi:i_r=0,i_tt=0,glint=0,glint_angle=40,glint_width=3");
  const float at = 40.0f * kPi / 180.0f;
  const glm::vec3 L = dir(0.1f, 0);
  const float on = sadeghi(m, L, dir(0.1f, at)).x, without = sadeghi(off, L, dir(0.1f, at)).x;
  const float away = sadeghi(m, L, dir(0.1f, at + 0.5f)).x;
  EXPECT_GT(on, 2 * without);
  EXPECT_GT(on, 2 * away);
}

TEST(SadeghiShading, SadeghiDefaultsAreTheThesisListing2) {
  // Kraft 2018, Listing 2: diffuse 0.4, the specular sum R + TT + TRT unweighted (1), no
  // ambient term, the glints' Gaussian at the TT lobe's azi_width (tt_width, 10 degrees).
  const sb::ShadingModel m = model("sadeghi");
  const sb::SadeghiParams p = m.paramsAs<sb::SadeghiParams>();
  EXPECT_FLOAT_EQ(p.sadeghiDiffuse, 0.4f);
  EXPECT_FLOAT_EQ(p.sadeghiSpecular, 1.0f);
  EXPECT_FLOAT_EQ(m.ambient, 0.0f);
  EXPECT_FLOAT_EQ(p.sadeghiGlintWidth, 10.0f * kPi / 180.0f);
  EXPECT_FLOAT_EQ(p.sadeghiGlintWidth, p.sadeghiTtWidth);
  auto glintWidth = [](const char* spec) { return params(spec).sadeghiGlintWidth; };
  EXPECT_FLOAT_EQ(glintWidth("sadeghi:tt_width=20"), 20.0f * kPi / 180.0f);
  EXPECT_FLOAT_EQ(glintWidth("sadeghi:glint_width=5"), 5.0f * kPi / 180.0f);
  EXPECT_FLOAT_EQ(model("sadeghi:ambient=0.12").ambient, 0.12f);
}

}  // namespace
