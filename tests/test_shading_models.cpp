// The hair shading models' math on the CPU (techniques/marschner/marschner.glsl,
// techniques/sadeghi/sadeghi.glsl compiled as C++): finite and non-negative everywhere, grazing
// and back-lit included; lobes where the papers put them; the spec's options and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "backends/device.h"
#include "base/errors.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "render/shading/shading_model.h"
#include "techniques/marschner/marschner.h"
#include "techniques/sadeghi/sadeghi.h"

namespace {

constexpr float kPi = 3.14159265358979f;
const glm::vec3 kTangent{0, 1, 0};
const glm::vec3 kBrown{0.55f, 0.35f, 0.2f};

// A direction at longitudinal angle theta (to the normal plane, towards the tip) and azimuth phi.
glm::vec3 dir(float theta, float phi) {
  return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

sb::ShadingModel model(const std::string& spec) { return sb::ShadingModel::fromSpec(spec); }

glm::vec3 marschner(const sb::ShadingModel& m, glm::vec3 L, glm::vec3 V, glm::vec3 c = kBrown) {
  return sb::glsl::marschner(kTangent, L, V, c, m.shift, m.width);
}
glm::vec3 sadeghi(const sb::ShadingModel& m, glm::vec3 L, glm::vec3 V, glm::vec3 c = kBrown) {
  return sb::glsl::sadeghi(kTangent, L, V, c, m.shift, m.width, m.intensity, m.glintWidth);
}

void expectFiniteAndBounded(glm::vec3 v, float bound, const std::string& where) {
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::isfinite(v[i])) << where;
    ASSERT_GE(v[i], 0.0f) << where;
    ASSERT_LE(v[i], bound) << where;
  }
}

// Every pair of directions on a grid, the poles (looking along the fibre: grazing), opposite
// directions (back-lit) and black and white strands: finite, >= 0 and under maxSpecular(),
// the colour invariant's bound.
TEST(ShadingModels, FiniteNonNegativeAndBoundedEverywhere) {
  for (const char* spec : {"marschner", "sadeghi", "marschner:alpha=20,beta=1,caustic=0.01",
                           "sadeghi:beta=1,glint=10,glint_width=1"}) {
    const sb::ShadingModel m = model(spec);
    const bool isMarschner = m.kind == sb::ShadingKind::Marschner;
    const float bound = m.maxSpecular();
    for (glm::vec3 color : {glm::vec3(0), glm::vec3(1), kBrown}) {
      for (int a = 0; a <= 12; ++a)
        for (int b = 0; b <= 12; ++b)
          for (int c = 0; c < 12; ++c) {
            const float ti = -kPi / 2 + kPi * a / 12.0f, tr = -kPi / 2 + kPi * b / 12.0f;
            const glm::vec3 L = dir(ti, 0), V = dir(tr, 2 * kPi * c / 12.0f);
            const glm::vec3 v = isMarschner ? marschner(m, L, V, color) : sadeghi(m, L, V, color);
            expectFiniteAndBounded(v, bound,
                                   std::string(spec) + " " + std::to_string(a) + "," +
                                       std::to_string(b) + "," + std::to_string(c));
          }
      for (auto [L, V] : {std::pair{kTangent, -kTangent},
                          {-kTangent, kTangent},
                          {kTangent, kTangent},
                          {dir(0.3f, 0), -dir(0.3f, 0)}}) {
        const glm::vec3 v = isMarschner ? marschner(m, L, V, color) : sadeghi(m, L, V, color);
        expectFiniteAndBounded(v, bound, std::string(spec) + " grazing/back-lit");
      }
    }
  }
}

// R: a single root gamma_i = -phi/2 with |2 dphi/dh| = 4 / cos(phi/2), so the paper's
// N_R(phi) = F(eta', eta'', gamma_i) cos(phi/2) / 4.
TEST(ShadingModels, MarschnerReflectionIsFresnelTimesCosHalfPhiOverFour) {
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
TEST(ShadingModels, MarschnerTransmissionPeaksBehindTheFibre) {
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

// The longitudinal lobes: with the eye and light in one azimuth (phi = 0, R dominant), the
// highlight peaks where theta_h = alpha_R (shifted towards the root for alpha < 0); TT's peak
// (phi = pi) is shifted by -alpha/2, the other way.
TEST(ShadingModels, LobesWhereThePapersPutThem) {
  for (const char* spec : {"marschner:alpha=-8", "sadeghi:alpha=-8,i_trt=0,i_tt=0"}) {
    const sb::ShadingModel m = model(spec);
    const bool isMarschner = m.kind == sb::ShadingKind::Marschner;
    float best = -1, bestTheta = 0;
    const float thetaI = 0.2f;
    for (int k = -400; k <= 400; ++k) {
      const float thetaR = k * 0.002f;
      const glm::vec3 L = dir(thetaI, 0), V = dir(thetaR, 0);
      const float v = (isMarschner ? marschner(m, L, V) : sadeghi(m, L, V)).x;
      if (v > best) best = v, bestTheta = thetaR;
    }
    // theta_h = (theta_i + theta_r) / 2 = alpha_R (TRT, at -3alpha/2, is weaker).
    EXPECT_NEAR((thetaI + bestTheta) / 2, m.shift.x, 0.03f) << spec;
  }
  const sb::ShadingModel tt = model("sadeghi:alpha=-8,i_r=0,i_trt=0");
  float best = -1, bestTheta = 0;
  for (int k = -400; k <= 400; ++k) {
    const float thetaR = k * 0.002f;
    const float v = sadeghi(tt, dir(0.2f, 0), dir(thetaR, kPi)).x;
    if (v > best) best = v, bestTheta = thetaR;
  }
  EXPECT_NEAR((0.2f + bestTheta) / 2, -tt.shift.x / 2, 0.03f);
  EXPECT_GT(tt.shift.y, 0.0f);
}

// Sadeghi's TRT carries the glints: I_g g'(xi_g; G_angle - phi) adds a peak at the glint angle.
TEST(ShadingModels, SadeghiGlintsPeakAtTheGlintAngle) {
  const sb::ShadingModel m = model("sadeghi:i_r=0,i_tt=0,glint=4,glint_angle=40,glint_width=3");
  const sb::ShadingModel off = model("sadeghi:i_r=0,i_tt=0,glint=0,glint_angle=40,glint_width=3");
  const float at = 40.0f * kPi / 180.0f;
  const glm::vec3 L = dir(0.1f, 0);
  const float on = sadeghi(m, L, dir(0.1f, at)).x, without = sadeghi(off, L, dir(0.1f, at)).x;
  const float away = sadeghi(m, L, dir(0.1f, at + 0.5f)).x;
  EXPECT_GT(on, 2 * without);
  EXPECT_GT(on, 2 * away);
}

TEST(ShadingModels, SadeghiDefaultsAreTheThesisListing2) {
  // Kraft 2018, Listing 2: diffuse 0.4, the specular sum R + TT + TRT unweighted (1), no
  // ambient term, the glints' Gaussian at the TT lobe's azi_width (tt_width, 10 degrees).
  const sb::ShadingModel m = model("sadeghi");
  EXPECT_FLOAT_EQ(m.material.x, 0.4f);
  EXPECT_FLOAT_EQ(m.material.y, 1.0f);
  EXPECT_FLOAT_EQ(m.material.w, 0.0f);
  EXPECT_FLOAT_EQ(m.glintWidth, 10.0f * kPi / 180.0f);
  EXPECT_FLOAT_EQ(m.glintWidth, m.width.w);
  EXPECT_FLOAT_EQ(model("sadeghi:tt_width=20").glintWidth, 20.0f * kPi / 180.0f);
  EXPECT_FLOAT_EQ(model("sadeghi:glint_width=5").glintWidth, 5.0f * kPi / 180.0f);
  EXPECT_FLOAT_EQ(model("sadeghi:ambient=0.12").material.w, 0.12f);
  EXPECT_FLOAT_EQ(model("marschner").material.y, 0.5f);  // Marschner keeps its own
}

TEST(ShadingModels, SpecsAndErrors) {
  EXPECT_EQ(model("kajiya-kay").kind, sb::ShadingKind::KajiyaKay);
  EXPECT_EQ(model("marschner:eta=1.6").shift.w, 1.6f);
  EXPECT_EQ(model("sadeghi").kind, sb::ShadingKind::Sadeghi);
  for (const char* bad : {"marschnr", "marschner:eta=0.5", "sadeghi:glint=-1", "kajiya-kay:x=1",
                          "marschner:beta=abc"}) {
    try {
      model(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const sb::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("shading model"), std::string::npos)
          << bad << ": " << e.what();
    }
  }
}

}  // namespace

namespace {

// Each model renders on both APIs, the two images within the baselines' tolerance of each other
// (max_abs 0.002), and the models differ from each other (the option reaches the shaders).
TEST(ShadingModelsRender, BothBackendsAgreeAndTheModelsDiffer) {
  std::map<std::string, sb::Image> gl;
  for (const char* spec : {"kajiya-kay", "marschner", "sadeghi", "chiang"}) {
    std::map<std::string, sb::Image> images;
    for (const char* backend : {"gl", "vulkan"}) {
      sb::RenderRequest req;
      req.scene = "curly:strands=60,points=16,seed=7";
      req.shadow = "dom:size=64";
      req.oit = "wavg";
      req.shading = spec;
      req.backend = backend;
      req.width = req.height = 48;
      req.warmup = 0;
      req.invariants = req.reference = true;
      try {
        const sb::RenderResult r = sb::runRender(req);
        EXPECT_EQ(r.shading, spec);
        ASSERT_TRUE(r.invariants && r.invariants->empty()) << spec << " " << backend;
        images[backend] = r.image;
      } catch (const sb::DeviceError& e) {
        GTEST_SKIP() << "backend unavailable: " << e.what();
      }
    }
    const sb::ImageError d = sb::compareImages(images["gl"], images["vulkan"]);
    EXPECT_LE(d.maxAbs, 0.002) << spec;
    gl[spec] = images["gl"];
  }
  EXPECT_GT(sb::compareImages(gl["kajiya-kay"], gl["marschner"]).maxAbs, 0.05);
  EXPECT_GT(sb::compareImages(gl["marschner"], gl["sadeghi"]).maxAbs, 0.05);
  EXPECT_GT(sb::compareImages(gl["sadeghi"], gl["chiang"]).maxAbs, 0.05);
}

}  // namespace
