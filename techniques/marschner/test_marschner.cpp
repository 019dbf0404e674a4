// marschner's own tests (picked up by the build from its folder, as techniques/*/test_*.cpp):
// its azimuthal terms as the paper derives them (marschner.glsl compiled as C++).
#include <gtest/gtest.h>

#include <cmath>

#include "render/shading/shading_model.h"
#include "techniques/marschner/marschner.h"
#include "tests/shading_test_util.h"

namespace {

using sbtest::kBrown;
using sbtest::kPi;

// R: a single root gamma_i = -phi/2 with |2 dphi/dh| = 4 / cos(phi/2), so the paper's
// N_R(phi) = F(eta', eta'', gamma_i) cos(phi/2) / 4.
TEST(MarschnerShading, MarschnerReflectionIsFresnelTimesCosHalfPhiOverFour) {
  const float eta = 1.55f;
  for (float phi : {0.0f, 0.5f, 1.5f, 2.5f, 3.1f}) {
    const glm::vec3 n = sb::glsl::marschnerN(0, phi, eta, eta, glm::vec3(0), 0.5f);
    const float expected = sb::glsl::marschnerFresnel(eta, eta, -phi / 2) * std::cos(phi / 2) / 4;
    EXPECT_NEAR(n.x, expected, 1e-5f) << phi;
  }
  // Fresnel at normal incidence: ((eta-1)/(eta+1))^2; total internal reflection: 1.
  EXPECT_NEAR(sb::glsl::marschnerFresnel(eta, eta, 0), std::pow((eta - 1) / (eta + 1), 2), 1e-6f);
  EXPECT_EQ(sb::glsl::marschnerFresnel(1 / eta, 1 / eta, 1.2f), 1.0f);
}

// TT is forward scattering: strongest at phi = pi (light passing through the fibre towards the
// eye) and absent at phi = 0 (no refracted path turns that far); absorption tints it: a dark
// strand transmits less, and the colour's channels keep their order.
TEST(MarschnerShading, MarschnerTransmissionPeaksBehindTheFibre) {
  const float eta = 1.55f;
  const glm::vec3 sigma = -glm::log(kBrown) / 4.0f;
  const glm::vec3 back = sb::glsl::marschnerN(1, kPi, eta, eta, sigma, 0.5f);
  const glm::vec3 side = sb::glsl::marschnerN(1, kPi / 2, eta, eta, sigma, 0.5f);
  const glm::vec3 front = sb::glsl::marschnerN(1, 0, eta, eta, sigma, 0.5f);
  EXPECT_GT(back.x, side.x);
  EXPECT_EQ(front.x, 0.0f);
  EXPECT_GT(back.x, back.y);
  EXPECT_GT(back.y, back.z);
  const glm::vec3 dark =
      sb::glsl::marschnerN(1, kPi, eta, eta, -glm::log(glm::vec3(0.1f)) / 4.0f, 0.5f);
  EXPECT_LT(dark.x, back.x);
}

// Its own defaults beside Sadeghi's (which shares the lobe options): specular 0.5, eta 1.55.
TEST(MarschnerShading, KeepsItsOwnDefaults) {
  const sb::ShadingModel m = sb::ShadingModel::fromSpec("marschner");
  const sb::MarschnerParams p = m.paramsAs<sb::MarschnerParams>();
  EXPECT_FLOAT_EQ(p.marschnerSpecular, 0.5f);
  EXPECT_FLOAT_EQ(p.marschnerEta, 1.55f);
  EXPECT_FLOAT_EQ(m.ambient, 0.12f);
}

}  // namespace
