// The window platforms (`--platform window`, GLFW) on GL and Vulkan: a window
// render equals the headless one, read back from the window's framebuffer or
// swapchain image; presents follow resizes with no validation message; without
// a display the CLI refuses with exit 2 and writes nothing.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "backends/device.h"
#include "backends/window.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "tests/test_util.h"
#include "tests/window_test_util.h"

namespace fs = std::filesystem;

namespace {

using sbtest::WindowTest;

std::string psnrText(const sb::ImageError& e) {
  if (e.identical()) return "identical";
  char text[32];
  std::snprintf(text, sizeof text, "PSNR %.2f dB", e.psnr);
  return text;
}

TEST_P(WindowTest, RenderEqualsHeadless) {
  sb::RenderRequest req;
  req.scene = "curly:strands=200,points=12,seed=3";
  req.shadow = "osm:maps=8";
  req.oit = "wboit";
  req.backend = GetParam();
  req.width = 64;
  req.height = 48;  // not square: a transposed or flipped read-back cannot pass
  req.repeat = 2;
  req.validation = true;
  const sb::RenderResult headless = sb::runRender(req);
  EXPECT_FALSE(headless.presented);
  req.platform = "window";
  const sb::RenderResult window = sb::runRender(req);

  ASSERT_TRUE(window.presented);
  EXPECT_EQ(window.presented->frames, 2);
  EXPECT_EQ(window.presented->ms.size(), 2u);
  EXPECT_NE(window.presented->how.find(GetParam() == "gl" ? "swap interval 0" : "present mode"),
            std::string::npos)
      << window.presented->how;
  // The same render: the texture behind the window is the headless image.
  EXPECT_TRUE(sb::compareImages(window.image, headless.image, 0.0).identical());
  // What the window showed, read back from it, against the headless PNG.
  ASSERT_EQ(window.presented->image.width, 64);
  ASSERT_EQ(window.presented->image.height, 48);
  const sb::ImageError e =
      sb::compareImages(window.presented->image, sbtest::asPng(headless.image), 0.0);
  std::cout << "[ window ] " << GetParam()
            << ": window read-back vs headless render: " << psnrText(e) << " ("
            << window.presented->how << ")\n";
  RecordProperty("window_vs_headless", psnrText(e));
  EXPECT_TRUE(e.identical() || e.psnr >= 45.0) << psnrText(e);

  // The JSON: headless's keys, plus how it was presented.
  const nlohmann::json hj = sb::renderJson(headless), wj = sb::renderJson(window);
  for (const auto& [key, value] : hj.items()) EXPECT_TRUE(wj.contains(key)) << key;
  EXPECT_EQ(wj.at("platform"), "window");
  EXPECT_EQ(wj.at("presented").at("frames"), 2);
  EXPECT_EQ(wj.at("presented").at("present_ms").at("samples").size(), 2u);
  EXPECT_GE(wj.at("presented").at("frame_ms").at("median").get<double>(),
            wj.at("frame_ms").at("median").get<double>());
}

// A texture cleared to one colour, shown at the window's size through resizes.
TEST_P(WindowTest, PresentFollowsResize) {
  sb::DeviceOptions o;
  o.backend = GetParam();
  o.platform = "window";
  o.validation = true;
  o.windowWidth = 40;
  o.windowHeight = 24;
  auto dev = sb::createDevice(o);
  ASSERT_NE(dev->window(), nullptr);
  EXPECT_EQ(dev->info().platform, "window");
  const sb::Texture t =
      dev->createTexture({"shown", sb::Owner::Frame, sb::Format::RGBA32F, 40, 24});
  dev->beginFrame();
  sb::PassDesc pass;
  pass.name = "clear";
  pass.color.push_back({t, sb::LoadOp::Clear, {0.2f, 0.6f, 1.5f, 1.0f}});
  dev->beginPass(pass);
  dev->endPass();
  dev->endFrame();

  auto expectShown = [&](uint32_t w, uint32_t h) {
    sb::PresentedImage img;
    ASSERT_TRUE(dev->present(t, &img));
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    ASSERT_EQ(img.rgba8.size(), std::size_t(w) * h * 4);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < img.rgba8.size(); i += 4)  // 0.2, 0.6, clamped 1.5
      wrong += img.rgba8[i] != 51 || img.rgba8[i + 1] != 153 || img.rgba8[i + 2] != 255;
    EXPECT_EQ(wrong, 0u) << w << "x" << h;
  };
  expectShown(40, 24);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(dev->present(t));  // frames in flight before a resize
  dev->window()->resize(72, 56);
  ASSERT_EQ(dev->window()->width(), 72u);
  expectShown(72, 56);
  dev->window()->resize(16, 16);
  expectShown(16, 16);
  // Minimized (where a window manager applies it; bare Xvfb has none): nothing shown.
  dev->window()->minimize(true);
  if (dev->window()->width() == 0) {
    EXPECT_FALSE(dev->present(t));
  }
  dev->window()->minimize(false);
  expectShown(16, 16);
  // Integer and array textures cannot be shown.
  const sb::Texture ints =
      dev->createTexture({"ints", sb::Owner::Frame, sb::Format::RGBA32UI, 4, 4});
  EXPECT_THROW(dev->present(ints), sb::DeviceError);
}

INSTANTIATE_TEST_SUITE_P(Backends, WindowTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// Without a display: a clear message, exit status 2, nothing written.
TEST(WindowNoDisplay, RenderRefusesAndWritesNothing) {
  const fs::path dir = sbtest::tempDir("nodisplay");
  for (const char* backend : {"gl", "vulkan"}) {
    const fs::path out = dir / (std::string(backend) + ".png");
    const std::string cmd =
        "env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SB_CLI) + " render --backend " +
        backend + " --platform window --size 32x32 --scene straight:strands=10 --out " +
        out.string() + " --json >" + (dir / "out").string() + " 2>" + (dir / "err").string();
    const int raw = std::system(cmd.c_str());
    EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 2) << backend;
    const std::string err = sbtest::readFile(dir / "err");
    EXPECT_NE(err.find("no display"), std::string::npos) << err;
    EXPECT_NE(err.find("xvfb-run"), std::string::npos) << err;
    EXPECT_TRUE(sbtest::readFile(dir / "out").empty());
    EXPECT_FALSE(fs::exists(out)) << backend;
  }
  fs::remove_all(dir);
}

}  // namespace
