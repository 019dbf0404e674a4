// The papers' claims about self-shadowing error, measured against the exact
// visibility (visibility-space RMSE, so shading noise does not count):
// occupancy maps beat deep opacity maps (3 layers) on a stray strand in front
// of a dense clump (occupancy paper, Fig. 5a); deep opacity maps (3 layers)
// beat opacity shadow maps (16 maps) on straight hair lit from the side
// (deep opacity maps paper). The figures are printed.
#include <gtest/gtest.h>

#include <iostream>

#include "gpu_test_util.h"
#include "harness/render.h"

namespace sb {
namespace {

double visibilityRmse(RenderRequest r, const std::string& shadow) {
  r.shadow = shadow;
  r.reference = true;
  const RenderResult out = runRender(r);
  const double rmse = out.visibilityError->rmse;
  std::cout << "[ measured ] " << r.backend << " " << r.scene << " " << shadow
            << ": visibility RMSE " << rmse << ", image RMSE " << out.imageError->rmse << "\n";
  return rmse;
}

class ShadowErrors : public sbtest::BackendTest {
 protected:
  RenderRequest request(const std::string& scene) {
    RenderRequest r;
    r.scene = scene;
    r.backend = GetParam();
    r.width = r.height = 128;
    r.repeat = 1;
    r.warmup = 0;
    return r;
  }
};

TEST_P(ShadowErrors, OccupancyBeatsDeepOpacityMapsOnAStrayStrand) {
  const RenderRequest r = request("stray:strands=3000");
  const double occupancy = visibilityRmse(r, "occupancy:size=256");
  const double dom = visibilityRmse(r, "dom:layers=3,size=256");
  EXPECT_LT(occupancy, dom);
}

TEST_P(ShadowErrors, DeepOpacityMapsBeatOpacityShadowMapsOnSideLitStraightHair) {
  RenderRequest r = request("straight:strands=2000,points=16");
  r.view.lightDirection = glm::vec3(-1.0f, 0.0f, 0.0f);  // from the side
  const double dom = visibilityRmse(r, "dom:layers=3,size=256");
  const double osm = visibilityRmse(r, "osm:maps=16,size=256");
  EXPECT_LT(dom, osm);
}

INSTANTIATE_TEST_SUITE_P(Backends, ShadowErrors, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace sb
