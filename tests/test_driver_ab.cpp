// `strandbench driver-ab`: a suite swept on the system's Mesa and on Mesa 25.0.7, each in a
// process of its own, and the triage page: the case whose image changed (a line
// rasterization tie in the fur's shadow map) first, with its heatmap and FLIP map, the
// unchanged one folded; the page loads in headless Chromium without console errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/browser_util.h"
#include "tests/test_util.h"

namespace {

namespace fs = std::filesystem;

TEST(DriverAb, PairsTheCasesAndShowsTheChangeFirst) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  const fs::path dir = sbtest::tempDir("driver-ab");
  const nlohmann::json suite = {
      {"name", "ab-test"},
      {"defaults",
       {{"scene", "fur:strands=2000,seed=4"},
        {"size", "96x96"},
        {"primitive", "lines"},
        {"repeat", 3},
        {"warmup", 0},
        {"backends", {"gl"}}}},
      {"groups", {{{"name", "fur"}, {"axes", {{"shadow", {"none", "shadowmap"}}}}}}}};
  std::ofstream(dir / "suite.json") << suite.dump(2);
  const auto r = sbtest::runCli("driver-ab " + (dir / "suite.json").string() +
                                " --b mesa-25.0 --out " + (dir / "ab").string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto ab = nlohmann::json::parse(sbtest::readFile(dir / "ab" / "ab.json"));
  EXPECT_EQ(ab["a"]["name"], "system");
  EXPECT_EQ(ab["b"]["name"], "mesa-25.0");
  EXPECT_NE(ab["b"]["version"].get<std::string>().find("Mesa 25.0.7"), std::string::npos);
  ASSERT_EQ(ab["pairs"].size(), 2u);
  const auto& first = ab["pairs"][0];
  EXPECT_EQ(first["id"], "fur/shadow=shadowmap,backend=gl");
  EXPECT_GT(first["change"]["max_abs"].get<double>(), 0.1);
  EXPECT_GT(first["change"]["flip_mean"].get<double>(), 0.0);
  EXPECT_EQ(ab["pairs"][1]["change"]["max_abs"], 0.0) << "shadow none: the same image";
  EXPECT_EQ(ab["changed"], 1);
  for (const char* k : {"heatmap", "flip"})
    EXPECT_TRUE(fs::exists(dir / "ab" / first["change"][k].get<std::string>())) << k;
  EXPECT_TRUE(first.contains("time_ratio_b_over_a"));
  EXPECT_TRUE(first["a"].contains("work") && first["b"].contains("work"));
  // The shadow map's depth pass: 66419 samples on 22.3.6, 66417 on 25.0.7 (at 256x256 maps
  // here: any difference in samples passed shows the rasterization change).
  EXPECT_NE(first["a"]["work"]["samples_passed"], first["b"]["work"]["samples_passed"]);

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
