// --primitive world: strands at their world width with analytic coverage. Sub-pixel strands
// keep their ink (the image's sum doubles with their thickness, where one-pixel ribbons stay
// the same: the control), GL and Vulkan agree, and the techniques that cannot draw it say so.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <string>

#include "backends/device.h"
#include "base/errors.h"
#include "harness/render.h"
#include "imaging/metrics.h"

namespace {

sb::RenderRequest request(const std::string& thickness, const std::string& primitive,
                          const std::string& backend = "gl") {
  sb::RenderRequest r;
  r.backend = backend;
  r.scene = "straight:strands=8,points=4,seed=3,head=0,thickness=" + thickness;
  r.shadow = "none";
  r.oit = "abuffer";
  r.primitive = primitive;
  r.width = r.height = 64;
  r.warmup = 0;
  return r;
}

double ink(const sb::Image& img) {
  double sum = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) sum += img.pixels[img.index(x, y, c)];
  return sum;
}

TEST(WorldPrimitive, SubPixelStrandsKeepTheirInkOnBothApis) {
  std::map<std::string, sb::Image> images;
  for (const char* backend : {"gl", "vulkan"}) {
    try {
      const double thin = ink(sb::runRender(request("0.004", "world", backend)).image);
      const sb::Image thickImage = sb::runRender(request("0.008", "world", backend)).image;
      const double ratio = ink(thickImage) / thin;
      const double control = ink(sb::runRender(request("0.008", "ribbons", backend)).image) /
                             ink(sb::runRender(request("0.004", "ribbons", backend)).image);
      std::cout << "[ measured ] " << backend << ": ink ratio for twice the thickness " << ratio
                << " (world), " << control << " (one-pixel ribbons, the control)\n";
      EXPECT_NEAR(ratio, 2.0, 0.1) << backend;
      EXPECT_GT(std::abs(control - 2.0), 0.1) << backend;
      images[backend] = thickImage;
    } catch (const sb::DeviceError& e) {
      GTEST_SKIP() << "backend unavailable: " << e.what();
    }
  }
  EXPECT_LE(sb::compareImages(images["gl"], images["vulkan"]).maxAbs, 0.002);
}

TEST(WorldPrimitive, TracedTechniquesRefuseIt) {
  sb::RenderRequest r = request("0.004", "world");
  r.oit = "rt";
  try {
    sb::runRender(r);
    ADD_FAILURE() << "--oit rt drew --primitive world";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--primitive world"), std::string::npos) << e.what();
  } catch (const sb::DeviceError& e) {
    GTEST_SKIP() << "backend unavailable: " << e.what();
  }
}

}  // namespace
