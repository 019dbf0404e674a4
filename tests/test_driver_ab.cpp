// `strandbench driver-ab`: a suite swept on the system's Mesa and on Mesa 25.0.7, each in a
// process of its own, and its triage page.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/browser_util.h"
#include "tests/test_util.h"

namespace {

namespace fs = std::filesystem;

// The quick suite's technique groups (every shadow and transparency technique, both APIs)
// on the system's Mesa and on Mesa 25.0.7: every case renders on both, the changed ones come
// first with their heatmap and FLIP map, and the page loads in headless Chromium.
TEST(DriverAb, QuickSuiteSystemAgainstMesa25) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  const fs::path dir = sbtest::tempDir("driver-ab");
  const auto r = sbtest::runCli("driver-ab " + std::string(SB_SOURCE_DIR) +
                                "/suites/quick.json --b mesa-25.0 --filter "
                                "'^(every-|shadows/|transparency/)' --out " +
                                (dir / "ab").string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto ab = nlohmann::json::parse(sbtest::readFile(dir / "ab" / "ab.json"));
  EXPECT_EQ(ab["a"]["name"], "system");
  EXPECT_EQ(ab["b"]["name"], "mesa-25.0");
  EXPECT_NE(ab["b"]["version"].get<std::string>().find("Mesa 25.0.7"), std::string::npos);
  const auto& pairs = ab["pairs"];
  // shadows 6, transparency 7, every-shadow 8, every-transparency 10: on gl and vulkan.
  EXPECT_EQ(pairs.size(), 62u);
  double last = 1e9;
  for (const auto& p : pairs) {
    EXPECT_FALSE(p["a"].contains("failed") || p["b"].contains("failed")) << p.dump();
    ASSERT_TRUE(p.contains("change")) << p["id"];
    EXPECT_LE(p["change"]["flip_mean"].get<double>(), last) << "sorted by the change";
    last = p["change"]["flip_mean"].get<double>();
    EXPECT_TRUE(p["a"].contains("work") && p["b"].contains("work")) << p["id"];
  }
  ASSERT_GT(ab["changed"].get<int>(), 0) << "Mesa 25.0.7 moves some pixels (docs/drivers.md)";
  const auto& first = pairs[0];
  EXPECT_GT(first["change"]["max_abs"].get<double>(), 0.0);
  for (const char* k : {"heatmap", "flip"})
    EXPECT_TRUE(fs::exists(dir / "ab" / first["change"][k].get<std::string>())) << k;

  if (!fs::exists(sbtest::kChromium))
    GTEST_SKIP() << sbtest::kChromium << " is not installed (apt-get install chromium)";
  const sbtest::PageLoad page = sbtest::loadPage(dir / "ab" / "ab.html", dir / "chromium");
  ASSERT_EQ(page.status, 0) << page.log;
  EXPECT_TRUE(page.console.empty()) << ::testing::PrintToString(page.console);
  for (const char* needle : {"Driver A/B: system (A) against mesa-25.0 (B)", "class=\"toggle\"",
                             ".heatmap.png", ".flip.png", "the same image", "<details"})
    EXPECT_NE(page.dom.find(needle), std::string::npos) << needle;
  const sbtest::ScreenshotVerdict shot = sbtest::inspectScreenshot(page.screenshot);
  EXPECT_FALSE(shot.blank) << shot.distinct << " colours, " << shot.inked << " inked";
  fs::remove_all(dir);
}

TEST(DriverAb, BadDriversAreRefused) {
  const auto same =
      sbtest::runCli("driver-ab suites/quick.json --a system --b system --out /tmp/x");
  EXPECT_EQ(same.status, 2);
  EXPECT_NE(same.err.find("the same driver"), std::string::npos) << same.err;
  const auto unknown = sbtest::runCli("driver-ab suites/quick.json --b no-such --out /tmp/x");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("scripts/drivers.sh"), std::string::npos) << unknown.err;
  EXPECT_FALSE(fs::exists("/tmp/x/ab.json"));
}

}  // namespace
