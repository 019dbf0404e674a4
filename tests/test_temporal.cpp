// Error under animation (render --animate) and each technique's own error:
// the flicker error is 0 for a technique that is the reference and not for one
// that is not; the papers' temporal claims, measured at small sizes (the full
// table: scripts/temporal-claims.sh); a technique's own error against the
// exact technique of the other family (0 for peeling and the A-buffer), read
// from a small sweep's results and reports.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "browser_util.h"
#include "gpu_test_util.h"
#include "harness/measures/animation/animation.h"
#include "harness/render.h"
#include "harness/settings.h"
#include "imaging/image.h"
#include "test_util.h"

namespace sb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

class Temporal : public sbtest::BackendTest {
 protected:
  RenderRequest request(const std::string& scene, const std::string& shadow,
                        const std::string& animate) {
    RenderRequest r;
    r.scene = scene;
    r.shadow = shadow;
    r.backend = GetParam();
    r.width = r.height = 128;
    r.repeat = 1;
    r.warmup = 0;
    r.reference = true;
    setFromText(r, *findSetting("animate"), animate);
    return r;
  }
  AnimationResult animate(const RenderRequest& r) {
    const RenderResult out = runRender(r);
    const AnimationResult* slice = out.measure<AnimationResult>();
    EXPECT_TRUE(slice);
    const AnimationResult a = slice ? *slice : AnimationResult{};
    std::cout << "[ measured ] " << r.backend << " " << r.scene << " " << r.shadow << " "
              << settingText(r, *findSetting("animate")) << ": flicker visibility "
              << a.visibilityFlicker << ", image " << a.imageFlicker.value_or(-1) << "\n";
    return a;
  }
};

// The reference against itself has no flicker and no per-frame error; a
// technique with error has both, and frame 0 is the still render.
TEST_P(Temporal, FlickerIsZeroExactlyForTheReference) {
  const std::string scene = "straight:strands=300,points=8,head=0";
  RenderRequest exact = request(scene, "exact:method=abuffer", "light-orbit:frames=3,degrees=20");
  exact.oit = "abuffer";
  const AnimationResult a = animate(exact);
  ASSERT_EQ(a.frames.size(), 3u);
  EXPECT_EQ(a.visibilityFlicker, 0.0);
  EXPECT_EQ(*a.imageFlicker, 0.0);
  EXPECT_GT(a.visibilityPixels, 0u);
  for (const AnimationFrame& f : a.frames) {
    EXPECT_EQ(f.visibilityRmse, 0.0) << f.frame;
    EXPECT_EQ(*f.imageRmse, 0.0) << f.frame;
  }
  EXPECT_DOUBLE_EQ(a.frames[2].degrees, 20.0);
  EXPECT_EQ(a.stripFrames, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(a.stripImages.size(), 3u);
  // The light moved: the reference's own frames differ (else flicker 0 says nothing).
  EXPECT_NE(a.stripReferences[0].pixels, a.stripReferences[2].pixels);

  const RenderResult osm =
      runRender(request(scene, "osm:maps=4", "light-orbit:frames=3,degrees=20"));
  const AnimationResult* oa = osm.measure<AnimationResult>();
  ASSERT_TRUE(oa);
  EXPECT_GT(oa->visibilityFlicker, 0.0);
  EXPECT_GT(*oa->imageFlicker, 0.0);
  EXPECT_EQ(oa->frames[0].visibilityRmse, osm.visibilityError->rmse);

  // A camera orbit moves the reference's image too.
  const RenderResult cam =
      runRender(request(scene, "osm:maps=4", "camera-orbit:frames=2,degrees=40"));
  const AnimationResult* ca = cam.measure<AnimationResult>();
  ASSERT_TRUE(ca);
  EXPECT_NE(ca->stripReferences[0].pixels, ca->stripReferences[1].pixels);
}

// Deep opacity maps paper: OSM's layering bands crawl as the light moves.
TEST_P(Temporal, OpacityShadowMapsFlickerMoreThanDeepOpacityMapsOnStraightHair) {
  const std::string orbit = "light-orbit:frames=8,degrees=30";
  RenderRequest osm = request("straight:strands=2000,points=16", "osm:maps=16,size=256", orbit);
  osm.view.lightDirection = glm::vec3(-1.0f, 0.0f, 0.0f);  // from the side
  RenderRequest dom = osm;
  dom.shadow = "dom:layers=3,size=256";
  EXPECT_GT(animate(osm).visibilityFlicker, animate(dom).visibilityFlicker);
}

// Occupancy paper, Fig. 5a: a stray strand makes DOM's layers jump.
TEST_P(Temporal, DeepOpacityMapsFlickerMoreThanOccupancyMapsOnAStrayStrand) {
  const std::string orbit = "light-orbit:frames=8,degrees=30";
  const RenderRequest dom = request("stray:strands=3000", "dom:layers=3,size=256", orbit);
  RenderRequest occupancy = dom;
  occupancy.shadow = "occupancy:size=256";
  EXPECT_GT(animate(dom).visibilityFlicker, animate(occupancy).visibilityFlicker);
}

INSTANTIATE_TEST_SUITE_P(Backends, Temporal, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// Bad animation input: exit status 2, a message naming the option, nothing written.
TEST(AnimateInput, RefusedWithClearMessages) {
  const fs::path dir = sbtest::tempDir("animate-bad");
  const std::string base = "render --scene straight:strands=20,points=4 --size 16x16 --strip " +
                           (dir / "s.png").string() + " ";
  for (const auto& [args, needles] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"--animate light-orbit", {"--animate", "needs --reference"}},
           {"--reference", {"--strip needs --animate"}},
           {"--reference --animate light-orbitt", {"--animate", "did you mean 'light-orbit'"}},
           {"--reference --animate light-orbit:frames=1",
            {"--animate", "frames must be in 2..1000"}},
           {"--reference --animate camera-orbit:degrees=400", {"--animate", "[-360, 360]"}},
           {"--reference --animate light-orbit:speed=2",
            {"--animate", "unknown option 'speed'"}}}) {
    const sbtest::CliResult r = sbtest::runCli(base + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "s.png")) << args;
  }
  // And a good one writes the strip: two frames side by side over the reference's.
  const sbtest::CliResult ok =
      sbtest::runCli(base + "--reference --animate camera-orbit:frames=2,degrees=10");
  ASSERT_EQ(ok.status, 0) << ok.err;
  const Image strip = readImage((dir / "s.png").string());
  EXPECT_EQ(strip.width, 2 * 16 + 2);
  EXPECT_EQ(strip.height, 2 * 16 + 2);
  fs::remove_all(dir);
}

// One small suite: transparency techniques over DOM shadows, shadow techniques
// over opaque hair, one animated case. Its results, CSV, Markdown and HTML.
const char* kOwnSuite = R"({
  "name": "own",
  "defaults": {"scene": "clustered:strands=120,points=8,head=0,alpha=0.4,clusters=6",
               "size": "48x48", "repeat": 2, "warmup": 0, "reference": true,
               "backends": ["gl"]},
  "groups": [
    {"name": "transparency", "shadow": "dom:layers=3",
     "axes": {"oit": ["peel", "abuffer", "wboit", "none"]}},
    {"name": "shadows", "axes": {"shadow": ["exact", "osm:maps=8"]}},
    {"name": "animated", "shadow": "osm:maps=8",
     "axes": {"animate": ["light-orbit:frames=3,degrees=20"]}}
  ]
})";

std::vector<std::map<std::string, std::string>> csvRows(const std::string& text) {
  std::vector<std::vector<std::string>> lines;
  std::vector<std::string> row(1);
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
        row.back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        row.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.emplace_back();
    } else if (c == '\n') {
      lines.push_back(row);
      row.assign(1, "");
    } else {
      row.back() += c;
    }
  }
  std::vector<std::map<std::string, std::string>> out;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::map<std::string, std::string> m;
    for (std::size_t k = 0; k < lines[0].size() && k < lines[i].size(); ++k)
      m[lines[0][k]] = lines[i][k];
    out.push_back(m);
  }
  return out;
}

TEST(OwnError, ZeroForTheExactTechniquesAndReportedForTheOthers) {
  try {
    createDevice({.backend = "gl", .platform = "egl"});
  } catch (const DeviceError& e) {
    GTEST_SKIP() << "backend unavailable: " << e.what();
  }
  const fs::path dir = sbtest::tempDir("own");
  std::ofstream(dir / "own.json") << kOwnSuite;
  const sbtest::CliResult run =
      sbtest::runCli("sweep " + (dir / "own.json").string() + " --out " + (dir / "run").string());
  ASSERT_EQ(run.status, 0) << run.err;
  const json doc = json::parse(sbtest::readFile(dir / "run" / "results.json"));
  std::map<std::string, json> byId;
  for (const json& r : doc["results"]) byId[r["case"]["id"]] = r;
  auto own = [&](const std::string& id) { return byId.at(id)["error"]["own"]; };
  // The total error: error.image and error.visibility, written once.
  auto total = [&](const std::string& id) { return byId.at(id)["error"]; };

  // Peeling and the A-buffer are exact transparency: their own error is 0
  // though their total error (DOM's shadows) is not.
  for (const char* id :
       {"transparency/oit=peel,backend=gl", "transparency/oit=abuffer,backend=gl"}) {
    EXPECT_EQ(own(id)["technique"], "transparency") << id;
    EXPECT_EQ(own(id)["reference"]["shadow"], "dom:layers=3") << id;
    EXPECT_EQ(own(id)["image"]["rmse"], 0.0) << id;
    EXPECT_EQ(own(id)["image"]["flip"]["mean"], 0.0) << id;
    EXPECT_GT(total(id)["image"]["rmse"].get<double>(), 0.0) << id;
    EXPECT_FALSE(byId.at(id)["error"].contains("total")) << id;  // no second copy
  }
  // An approximate transparency technique has an own error, smaller than its
  // total here, where the total adds DOM's shadow error.
  const std::string wboit = "transparency/oit=wboit,backend=gl";
  EXPECT_GT(own(wboit)["image"]["rmse"].get<double>(), 0.0);
  EXPECT_NE(own(wboit)["image"]["rmse"], total(wboit)["image"]["rmse"]);
  // Exact shadows over opaque hair: own 0; OSM: own > 0, its visibility error unchanged.
  EXPECT_EQ(own("shadows/shadow=exact,backend=gl")["image"]["rmse"], 0.0);
  const std::string osm = "shadows/shadow=osm:maps=8,backend=gl";
  EXPECT_EQ(own(osm)["technique"], "shadow");
  EXPECT_EQ(own(osm)["reference"]["oit"], "none");
  EXPECT_GT(own(osm)["image"]["rmse"].get<double>(), 0.0);
  EXPECT_EQ(own(osm)["visibility"], total(osm)["visibility"]);

  // The animated case: per-frame errors, flicker, a strip image.
  const json& anim = byId.at("animated/animate=light-orbit:frames=3,degrees=20,backend=gl");
  EXPECT_EQ(anim["animation"]["per_frame"].size(), 3u);
  EXPECT_GT(anim["animation"]["flicker"]["visibility"].get<double>(), 0.0);
  EXPECT_TRUE(fs::is_regular_file(dir / "run" / anim["images"]["animation"].get<std::string>()));
  EXPECT_FALSE(byId.at(osm)["error"]["by_eye_layers"].empty());

  // The reports show both, labelled.
  const auto rows = csvRows(sbtest::readFile(dir / "run" / "results.csv"));
  ASSERT_EQ(rows.size(), doc["results"].size());
  for (const auto& row : rows) {
    const json& r = byId.at(row.at("case_id"));
    EXPECT_EQ(row.at("own_technique"), r["error"]["own"]["technique"]);
    EXPECT_DOUBLE_EQ(std::stod(row.at("own_image_rmse")),
                     r["error"]["own"]["image"]["rmse"].get<double>());
    EXPECT_DOUBLE_EQ(std::stod(row.at("image_rmse")), r["error"]["image"]["rmse"].get<double>());
  }
  EXPECT_EQ(rows.back().at("animation"), "light-orbit");
  const std::string md = sbtest::readFile(dir / "run" / "report.md");
  for (const char* label :
       {"Image RMSE (total)", "Image RMSE (own)", "FLIP mean (own)", "Own error of",
        "## Which technique within which budget", "## Error under animation", "Flicker visibility"})
    EXPECT_NE(md.find(label), std::string::npos) << label;

  // The real report in headless Chromium: the new charts present and labelled.
  if (fs::exists(sbtest::kChromium)) {
    const sbtest::PageLoad page = sbtest::loadPage(dir / "run" / "report.html", dir / "chromium");
    ASSERT_EQ(page.status, 0) << page.log;
    EXPECT_TRUE(page.console.empty()) << ::testing::PrintToString(page.console);
    for (const char* needle :
         {"class=\"chart-animation\"", "class=\"chart-depth-complexity\"", "metric-flip",
          "class=\"point-label\"", "class=\"error-bar\"", "Most accurate by FLIP",
          ">wboit + dom:layers=3</text>", "Image RMSE (own)", "animation strip"})
      EXPECT_NE(page.dom.find(needle), std::string::npos) << needle;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sb
