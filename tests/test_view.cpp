// `strandbench view` driven by --script on GL and Vulkan (under a display):
// techniques switched, the light moved, the camera orbited, a screenshot and
// its JSON written; the JSON's `render` command, run headless, reproduces the
// screenshot. Without a display, or with a bad script: exit 2, nothing written.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "imaging/image.h"
#include "imaging/metrics.h"
#include "tests/test_util.h"
#include "tests/window_test_util.h"

namespace fs = std::filesystem;

namespace {

// Runs a shell command line; the exit status, stdout and stderr.
sbtest::CliResult shell(const std::string& cmd, const fs::path& dir) {
  const int raw = std::system(
      (cmd + " >" + (dir / "stdout").string() + " 2>" + (dir / "stderr").string()).c_str());
  sbtest::CliResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = sbtest::readFile(dir / "stdout");
  r.err = sbtest::readFile(dir / "stderr");
  return r;
}

std::string shellQuoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

const char* kScript = R"(# switch the shadow technique twice and the transparency once,
# move the light, orbit and zoom, then a screenshot of the technique and one of the error
0    key S          # avsm -> dc (the registry's order: none, then by name)
50   key S          # dc -> dom
100  key T          # stochastic -> wavg
150  drag right 60 -25
200  drag left 40 15
250  scroll 1
300  screenshot shot
350  key C
360  key C          # technique -> reference -> error heatmap
400  screenshot error
420  resize 96 64   # the image follows the window
430  screenshot resized
450  quit
)";

class ViewTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!sbtest::haveDisplay()) GTEST_SKIP() << sbtest::kNoDisplay;
  }
};

TEST_P(ViewTest, ScriptedSessionScreenshotIsReproducedByItsRenderCommand) {
  const fs::path dir = sbtest::tempDir("view");
  const fs::path script = dir / "session.txt";
  std::ofstream(script) << kScript;
  const std::string backend = GetParam();
  const sbtest::CliResult r =
      shell(std::string(SB_CLI) + " view --backend " + backend +
                " --validation --scene curly:strands=150,points=12,seed=5,alpha=0.4 --shadow avsm "
                "--oit stochastic --shading marschner --size 128x96 --script " +
                script.string() + " --screenshot-dir " + (dir / "shots").string(),
            dir);
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;

  const nlohmann::json j = nlohmann::json::parse(sbtest::readFile(dir / "shots" / "shot.json"));
  EXPECT_EQ(j.at("shown"), "technique");
  EXPECT_EQ(j.at("case").at("shadow"), "dom");
  EXPECT_EQ(j.at("case").at("oit"), "wavg");
  EXPECT_EQ(j.at("case").at("backend"), backend);
  EXPECT_TRUE(j.at("case").contains("light_direction"));
  EXPECT_TRUE(j.at("case").contains("camera_eye"));
  EXPECT_EQ(j.at("suite").at("defaults").at("backends"), nlohmann::json::array({backend}));
  EXPECT_EQ(j.at("case").at("size"), "128x96");
  // view takes --shading as render does; the screenshot's case and command keep it.
  EXPECT_EQ(j.at("case").at("shading").get<std::string>().rfind("marschner", 0), 0u);
  const std::string line = j.at("render").get<std::string>();
  EXPECT_EQ(line.rfind("strandbench render ", 0), 0u) << line;
  EXPECT_NE(line.find("--light-direction"), std::string::npos) << line;

  // The JSON's command, run headless (its own --out moved to a new file).
  std::vector<std::string> args = j.at("render_args").get<std::vector<std::string>>();
  ASSERT_GE(args.size(), 4u);
  ASSERT_EQ(args[args.size() - 2], "--out");
  args.back() = (dir / "again.png").string();
  std::string cmd = SB_CLI;
  for (std::size_t i = 1; i < args.size(); ++i) {
    cmd += ' ';  // appended, not " " + ...: GCC 12 warns (-Wrestrict) on that
    cmd += shellQuoted(args[i]);
  }
  const sbtest::CliResult again = shell(cmd, dir);
  ASSERT_EQ(again.status, 0) << cmd << "\n" << again.err;
  const sb::Image shot = sb::readImage((dir / "shots" / "shot.png").string());
  const sb::Image rendered = sb::readImage((dir / "again.png").string());
  EXPECT_EQ(shot.width, 128);
  EXPECT_EQ(shot.height, 96);
  const sb::ImageError e = sb::compareImages(shot, rendered, 0.0);
  char figure[48] = "identical";
  if (!e.identical()) std::snprintf(figure, sizeof figure, "PSNR %.2f dB", e.psnr);
  std::cout << "[ view ] " << backend
            << ": screenshot vs its render command run headless: " << figure << "\n";
  RecordProperty("screenshot_vs_render", figure);
  EXPECT_TRUE(e.identical() || e.psnr >= 45.0) << figure;

  // Its one-case suite runs as it is.
  std::ofstream(dir / "suite.json") << j.at("suite").dump();
  const sbtest::CliResult sweep =
      shell(std::string(SB_CLI) + " sweep " + (dir / "suite.json").string() + " --out " +
                (dir / "sweep").string(),
            dir);
  EXPECT_EQ(sweep.status, 0) << sweep.err;
  EXPECT_TRUE(fs::exists(dir / "sweep" / "results.json"));

  // The error heatmap's command reproduces it too.
  const nlohmann::json err = nlohmann::json::parse(sbtest::readFile(dir / "shots" / "error.json"));
  EXPECT_EQ(err.at("shown"), "error");
  const std::string errLine = err.at("render").get<std::string>();
  EXPECT_NE(errLine.find(" --reference "), std::string::npos) << errLine;
  EXPECT_NE(errLine.find(" --heatmap "), std::string::npos) << errLine;
  EXPECT_TRUE(err.at("report").contains("error"));
  const sb::Image resized = sb::readImage((dir / "shots" / "resized.png").string());
  EXPECT_EQ(resized.width, 96);
  EXPECT_EQ(resized.height, 64);

  // The README's screenshot comes from this session (SB_DOCS_SCREENSHOT=1).
  if (backend == "vulkan" && std::getenv("SB_DOCS_SCREENSHOT"))
    fs::copy_file(dir / "shots" / "shot.png", fs::path(SB_SOURCE_DIR) / "docs" / "view.png",
                  fs::copy_options::overwrite_existing);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

TEST(ViewBadInput, NoDisplayOrBadScriptWritesNothing) {
  const fs::path dir = sbtest::tempDir("viewbad");
  const fs::path shots = dir / "shots";
  const sbtest::CliResult noDisplay =
      shell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SB_CLI) +
                " view --size 32x32 --scene straight:strands=10 --screenshot-dir " + shots.string(),
            dir);
  EXPECT_EQ(noDisplay.status, 2);
  EXPECT_NE(noDisplay.err.find("no display"), std::string::npos) << noDisplay.err;
  EXPECT_FALSE(fs::exists(shots));

  const fs::path script = dir / "bad.txt";
  std::ofstream(script) << "0 key S\n100 screenshot ok\n50 key T\n";
  const sbtest::CliResult bad = shell(std::string(SB_CLI) + " view --script " + script.string() +
                                          " --screenshot-dir " + shots.string(),
                                      dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find(script.string() + ":3"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(shots));
  std::ofstream(script) << "0 jump\n";
  const sbtest::CliResult unknown =
      shell(std::string(SB_CLI) + " view --script " + script.string() + " --screenshot-dir " +
                shots.string(),
            dir);
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("unknown action 'jump'"), std::string::npos) << unknown.err;
  EXPECT_FALSE(fs::exists(shots));
  fs::remove_all(dir);
}

// A script's key must be one the viewer acts on: a typo is refused (exit 2, the
// closest key named, nothing written), not pressed silently. (Each script ends
// with quit, so that a viewer that accepts the key exits instead of waiting.)
TEST(ViewBadInput, UnknownKeyIsRefused) {
  const fs::path dir = sbtest::tempDir("viewkey");
  const fs::path shots = dir / "shots";
  const fs::path script = dir / "keys.txt";
  for (const auto& [line, needles] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"500 key Foo\n600 quit\n", {":1: ", "unknown key 'Foo'", "Up", "Escape"}},
           {"0 key S\n10 key Uo shift\n20 quit\n",
            {":2: ", "unknown key 'Uo'", "did you mean 'Up'"}}}) {
    std::ofstream(script) << line;
    const sbtest::CliResult r = shell(std::string(SB_CLI) + " view --script " + script.string() +
                                          " --screenshot-dir " + shots.string(),
                                      dir);
    EXPECT_EQ(r.status, 2) << line;
    for (const std::string& n : needles)
      EXPECT_NE(r.err.find(n), std::string::npos) << line << r.err << "\nlacks " << n;
    EXPECT_FALSE(fs::exists(shots));
  }
  fs::remove_all(dir);
}

// The arrow keys on a technique without a steppable option, or at its limit,
// say so and change nothing (no state line, no new render); a step that
// changes something prints the state.
TEST(ViewArrows, NothingToStepIsSaidAndChangesNothing) {
  if (!sbtest::haveDisplay()) GTEST_SKIP() << sbtest::kNoDisplay;
  const fs::path dir = sbtest::tempDir("viewarrows");
  const fs::path script = dir / "arrows.txt";
  std::ofstream(script) << "0 key Up\n50 key Right\n100 key Down\n150 quit\n";
  const sbtest::CliResult r =
      shell(std::string(SB_CLI) +
                " view --backend gl --scene straight:strands=20,points=4 --size 32x32 "
                "--shadow dom:layers=31 --oit wsum --script " +
                script.string() + " --screenshot-dir " + dir.string(),
            dir);
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("view: shadow dom:layers=31: layers is at its largest (1..31); unchanged"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("view: oit wsum has no option the arrow keys step; unchanged"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("view: shadow dom:layers=31, oit wsum"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("view: shadow dom:layers=30, oit wsum"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

}  // namespace
