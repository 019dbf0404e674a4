// kajiya-kay's own tests (picked up by the build from its folder, as techniques/*/test_*.cpp):
// its two factors where the paper puts them, and its model's CPU form from its options.
#include <gtest/gtest.h>

#include <cmath>

#include "render/shading/shading_model.h"
#include "techniques/kajiya_kay/kajiya_kay.h"
#include "tests/shading_test_util.h"

namespace {

using sbtest::dir;
using sbtest::kTangent;

// Diffuse: sin(T, L); specular: 1 on the cone of reflection (V at -theta_i, any azimuth), less
// off it, and sharper for a larger exponent.
TEST(KajiyaKayShading, DiffuseIsSinAndTheHighlightSitsOnTheReflectionCone) {
  const glm::vec3 L = dir(0.4f, 0);
  for (float phi : {0.0f, 1.0f, 2.5f}) {
    const glm::vec2 on = sb::glsl::kajiyaKay(kTangent, L, dir(-0.4f, phi), 40.0f);
    EXPECT_NEAR(on.x, std::cos(0.4f), 1e-6f);
    EXPECT_NEAR(on.y, 1.0f, 1e-5f) << phi;
    const glm::vec2 off = sb::glsl::kajiyaKay(kTangent, L, dir(0.1f, phi), 40.0f);
    EXPECT_LT(off.y, 0.5f) << phi;
    EXPECT_GT(sb::glsl::kajiyaKay(kTangent, L, dir(0.1f, phi), 4.0f).y, off.y) << phi;
  }
}

// The model's CPU form is diffuse * sin * colour + specular * highlight, from its options.
TEST(KajiyaKayShading, DirectWeighsTheFactorsByTheOptions) {
  const sb::ShadingModel m = sb::ShadingModel::fromSpec("kajiya-kay:diffuse=2,specular=0.5");
  const glm::vec3 L = dir(0.4f, 0), V = dir(-0.3f, 1.0f), c{0.5f, 0.25f, 1.0f};
  const glm::vec2 kk = sb::glsl::kajiyaKay(kTangent, L, V, 40.0f);
  const glm::vec3 got = m.direct(kTangent, L, V, c);
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(got[i], 2.0f * kk.x * c[i] + 0.5f * kk.y);
  EXPECT_FLOAT_EQ(m.maxDirect, 2.5f);
  EXPECT_FLOAT_EQ(m.ambient, 0.12f);
}

}  // namespace
