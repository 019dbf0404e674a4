// The viewer's overlay (key O) on GL and Vulkan, under a display: what the
// window shows (read back from it, a screenshot's NAME.window.png) differs
// from the render (NAME.png, which stays the technique's image) only in a box
// in the top-left corner, and equals it with the overlay off; a large window
// doubles the text; in reference mode the overlay says whose numbers it shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "imaging/image.h"
#include "tests/test_util.h"
#include "tests/window_test_util.h"

namespace fs = std::filesystem;

namespace {

class ViewOverlayTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!sbtest::haveDisplay()) GTEST_SKIP() << sbtest::kNoDisplay;
  }
};

// Where the window's image differs from the render's PNG by more than one
// 8-bit step (the window rounds the float image itself): the bounding box
// ([x0, x1) x [y0, y1), rows from the top) and how many pixels.
struct Differences {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = 0, y1 = 0;
  std::size_t count = 0;
  bool any() const { return count > 0; }
};

Differences differences(const sb::Image& window, const sb::Image& render) {
  Differences d;
  for (int y = 0; y < render.height; ++y)
    for (int x = 0; x < render.width; ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c)
        differs |= std::fabs(window.at(x, y, c) - render.at(x, y, c)) > 1.5f / 255.0f;
      if (!differs) continue;
      ++d.count;
      d.x0 = std::min(d.x0, x);
      d.y0 = std::min(d.y0, y);
      d.x1 = std::max(d.x1, x + 1);
      d.y1 = std::max(d.y1, y + 1);
    }
  return d;
}

TEST_P(ViewOverlayTest, OverlayChangesOnlyTheTopLeftBoxOfThePresentedImage) {
  const fs::path dir = sbtest::tempDir("view-overlay");
  std::ofstream(dir / "session.txt") << "0 screenshot on\n"
                                        "10 key O\n"
                                        "20 screenshot off\n"
                                        "30 key O\n"
                                        "40 key C\n"  // the reference: the overlay says so
                                        "50 screenshot reference\n"
                                        "60 key C shift\n"
                                        "70 resize 960 720\n"  // large enough for 2x text
                                        "80 screenshot large\n"
                                        "90 quit\n";
  const std::string backend = GetParam();
  const sbtest::CliResult r = sbtest::runCli(
      "view --backend " + backend +
      " --validation --scene curly:strands=60,points=8,seed=5,alpha=0.5 --shadow osm --oit "
      "wboit --size 400x300 --script " +
      (dir / "session.txt").string() + " --screenshot-dir " + (dir / "shots").string());
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  auto json = [&](const std::string& name) {
    return nlohmann::json::parse(sbtest::readFile(dir / "shots" / (name + ".json")));
  };
  auto image = [&](const std::string& file) {
    return sb::readImage((dir / "shots" / file).string());
  };

  // On: a box from the corner's margin, well inside the picture; everything else equal.
  const nlohmann::json on = json("on");
  EXPECT_TRUE(on.at("overlay").get<bool>());
  EXPECT_EQ(on.at("window_image"), (dir / "shots" / "on.window.png").string());
  const sb::Image render = image("on.png"), shown = image("on.window.png");
  ASSERT_EQ(shown.width, 400);
  ASSERT_EQ(shown.height, 300);
  const Differences d = differences(shown, render);
  ASSERT_TRUE(d.any()) << "the overlay changed nothing";
  std::cout << "[ overlay ] " << backend << ": box " << d.x0 << "," << d.y0 << " to " << d.x1 << ","
            << d.y1 << " of 400x300, " << d.count << " pixels differ\n";
  // The glyphs start at the margin and padding (10 pixels at 1x); the dark box
  // around them changes nothing where the picture is black (its background).
  EXPECT_LE(d.x0, 12);
  EXPECT_LE(d.y0, 12);
  EXPECT_GE(d.x1, 100);  // the text's lines, not a speck
  EXPECT_GE(d.y1, 60);
  EXPECT_LT(d.x1, 400 * 3 / 4);
  EXPECT_LT(d.y1, 300 * 3 / 4);
  // The render itself is the technique's: the same image the overlay was off for.
  const sb::Image renderOff = image("off.png");
  EXPECT_FALSE(differences(renderOff, render).any());

  // Off: the window shows the render.
  EXPECT_FALSE(json("off").at("overlay").get<bool>());
  EXPECT_FALSE(json("off").contains("overlay_text"));
  const Differences off = differences(image("off.window.png"), renderOff);
  EXPECT_FALSE(off.any()) << off.count << " pixels differ with the overlay off";

  // The reference shown: the overlay names it and whose the numbers are.
  const nlohmann::json ref = json("reference");
  EXPECT_EQ(ref.at("shown"), "reference");
  const auto text = ref.at("overlay_text").get<std::vector<std::string>>();
  ASSERT_GE(text.size(), 4u);
  EXPECT_NE(text[0].find("REFERENCE shown"), std::string::npos) << text[0];
  EXPECT_EQ(text[1],
            "ref shadow " + ref.at("report").at("reference").at("shadow").get<std::string>());
  EXPECT_EQ(text[2], "ref oit " + ref.at("report").at("reference").at("oit").get<std::string>());
  EXPECT_NE(text[3].find("the technique's"), std::string::npos) << text[3];
  EXPECT_TRUE(std::any_of(text.begin(), text.end(), [](const std::string& t) {
    return t.rfind("PSNR ", 0) == 0;
  })) << "the PSNR is known once the reference is";
  const Differences refBox = differences(image("reference.window.png"), image("reference.png"));
  EXPECT_LE(refBox.x0, 12);
  EXPECT_GT(refBox.y1, d.y1) << "more lines";
  EXPECT_LT(refBox.x1, 400) << "the reference's lines fit a 400-pixel window";

  // A large window: the text at twice the size, still in the corner.
  const Differences large = differences(image("large.window.png"), image("large.png"));
  ASSERT_TRUE(large.any());
  EXPECT_LE(large.x0, 24);
  EXPECT_LE(large.y0, 24);
  EXPECT_GE(large.x1 - large.x0, 1.6 * (d.x1 - d.x0)) << "2x text in a 960x720 window";
  EXPECT_LT(large.x1, 960 * 3 / 4);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewOverlayTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
