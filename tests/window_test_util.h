// Helpers for the window platform's tests: they need a display (scripts/test.sh
// runs them under xvfb-run) and skip with the reason without one.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "backends/device.h"
#include "imaging/image.h"

namespace sbtest {

inline bool haveDisplay() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

inline const char* kNoDisplay =
    "no display (DISPLAY and WAYLAND_DISPLAY unset): window tests run under xvfb-run, as "
    "scripts/test.sh does";

// A window test per backend: skipped without a display; any Vulkan validation
// message (a resize included) fails it.
class WindowTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!haveDisplay()) GTEST_SKIP() << kNoDisplay;
    messages_ = sb::validationMessageCount();
  }
  void TearDown() override {
    if (haveDisplay()) {
      EXPECT_EQ(sb::validationMessageCount(), messages_) << "Vulkan validation messages";
    }
  }
  std::size_t messages_ = 0;
};

// The image as its PNG holds it: round(clamp(v, 0, 1) * 255) / 255, alpha 1
// (imaging/image.h), which is what a window shows.
inline sb::Image asPng(sb::Image img) {
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    float v = img.pixels[i];
    v = std::isnan(v) ? 0.0f : std::fmin(std::fmax(v, 0.0f), 1.0f);
    img.pixels[i] = i % 4 == 3 ? 1.0f : float(std::lround(v * 255.0f)) / 255.0f;
  }
  return img;
}

}  // namespace sbtest
