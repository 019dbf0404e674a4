// The hair shading models on the CPU (each model's ShadingModel::direct, its shading.glsl's
// shadingDirect): finite, non-negative and bounded everywhere, grazing and back-lit included;
// lobes where the papers put them; the spec's options and errors. Each model's own tests are in
// its folder (techniques/<folder>/test_*.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "backends/device.h"
#include "base/errors.h"
#include "harness/measures/invariants/invariants.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "render/shading/shading_model.h"
#include "techniques/marschner/marschner.h"
#include "techniques/sadeghi/sadeghi.h"
#include "tests/shading_test_util.h"

namespace {

using sbtest::dir;
using sbtest::kBrown;
using sbtest::kPi;
using sbtest::kTangent;

sb::ShadingModel model(const std::string& spec) { return sb::ShadingModel::fromSpec(spec); }

glm::vec3 marschner(const sb::ShadingModel& m, glm::vec3 L, glm::vec3 V, glm::vec3 c = kBrown) {
  return sb::marschnerScattering(m.paramsAs<sb::MarschnerParams>(), kTangent, L, V, c);
}
glm::vec3 sadeghi(const sb::ShadingModel& m, glm::vec3 L, glm::vec3 V, glm::vec3 c = kBrown) {
  return sb::sadeghiSpecular(m.paramsAs<sb::SadeghiParams>(), kTangent, L, V, c);
}

void expectFiniteAndBounded(glm::vec3 v, float bound, const std::string& where) {
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::isfinite(v[i])) << where;
    ASSERT_GE(v[i], 0.0f) << where;
    ASSERT_LE(v[i], bound) << where;
  }
}

// Every pair of directions on a grid, the poles (looking along the fibre: grazing), opposite
// directions (back-lit) and black and white strands: finite, >= 0 and under maxDirect, the
// colour invariant's bound.
TEST(ShadingModels, FiniteNonNegativeAndBoundedEverywhere) {
  for (const char* spec :
       {"kajiya-kay", "marschner", "sadeghi", "marschner:alpha=20,beta=1,caustic=0.01",
        "sadeghi:beta=1,glint=10,glint_width=1", "kajiya-kay:shininess=1"}) {
    const sb::ShadingModel m = model(spec);
    const float bound = m.maxDirect;
    for (glm::vec3 color : {glm::vec3(0), glm::vec3(1), kBrown}) {
      for (int a = 0; a <= 12; ++a)
        for (int b = 0; b <= 12; ++b)
          for (int c = 0; c < 12; ++c) {
            const float ti = -kPi / 2 + kPi * a / 12.0f, tr = -kPi / 2 + kPi * b / 12.0f;
            const glm::vec3 L = dir(ti, 0), V = dir(tr, 2 * kPi * c / 12.0f);
            const glm::vec3 v = m.direct(kTangent, L, V, color);
            expectFiniteAndBounded(v, bound,
                                   std::string(spec) + " " + std::to_string(a) + "," +
                                       std::to_string(b) + "," + std::to_string(c));
          }
      for (auto [L, V] : {std::pair{kTangent, -kTangent},
                          {-kTangent, kTangent},
                          {kTangent, kTangent},
                          {dir(0.3f, 0), -dir(0.3f, 0)}}) {
        const glm::vec3 v = m.direct(kTangent, L, V, color);
        expectFiniteAndBounded(v, bound, std::string(spec) + " grazing/back-lit");
      }
    }
  }
}

// The longitudinal lobes: with the eye and light in one azimuth (phi = 0, R dominant), the
// highlight peaks where theta_h = alpha_R (shifted towards the root for alpha < 0); TT's peak
// (phi = pi) is shifted by -alpha/2, the other way.
TEST(ShadingModels, LobesWhereThePapersPutThem) {
  for (const char* spec : {"marschner:alpha=-8", "sadeghi:alpha=-8,i_trt=0,i_tt=0"}) {
    const sb::ShadingModel m = model(spec);
    const bool isMarschner = std::string(spec).rfind("marschner", 0) == 0;
    float best = -1, bestTheta = 0;
    const float thetaI = 0.2f;
    for (int k = -400; k <= 400; ++k) {
      const float thetaR = k * 0.002f;
      const glm::vec3 L = dir(thetaI, 0), V = dir(thetaR, 0);
      const float v = (isMarschner ? marschner(m, L, V) : sadeghi(m, L, V)).x;
      if (v > best) best = v, bestTheta = thetaR;
    }
    // theta_h = (theta_i + theta_r) / 2 = alpha_R (TRT, at -3alpha/2, is weaker).
    const float alphaR = isMarschner ? m.paramsAs<sb::MarschnerParams>().marschnerAlpha.x
                                     : m.paramsAs<sb::SadeghiParams>().sadeghiAlpha.x;
    EXPECT_NEAR((thetaI + bestTheta) / 2, alphaR, 0.03f) << spec;
  }
  const sb::ShadingModel tt = model("sadeghi:alpha=-8,i_r=0,i_trt=0");
  float best = -1, bestTheta = 0;
  for (int k = -400; k <= 400; ++k) {
    const float thetaR = k * 0.002f;
    const float v = sadeghi(tt, dir(0.2f, 0), dir(thetaR, kPi)).x;
    if (v > best) best = v, bestTheta = thetaR;
  }
  const glm::vec4 alpha = tt.paramsAs<sb::SadeghiParams>().sadeghiAlpha;
  EXPECT_NEAR((0.2f + bestTheta) / 2, -alpha.x / 2, 0.03f);
  EXPECT_GT(alpha.y, 0.0f);
}

TEST(ShadingModels, SpecsAndErrors) {
  // Each model binds its own GLSL and block.
  EXPECT_EQ(model("kajiya-kay").shader, "techniques/kajiya_kay/shading.glsl");
  EXPECT_EQ(model("marschner:eta=1.6").paramsAs<sb::MarschnerParams>().marschnerEta, 1.6f);
  EXPECT_EQ(model("sadeghi").shader, "techniques/sadeghi/shading.glsl");
  EXPECT_THROW(model("sadeghi").paramsAs<sb::MarschnerParams>(), std::logic_error);
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
        const sb::InvariantsResult* inv = r.measure<sb::InvariantsResult>();
        ASSERT_TRUE(inv && inv->failures.empty()) << spec << " " << backend;
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
