// The anti-aliased exact reference (`--reference aa:samples=S`,
// docs/ground-truth.md "The anti-aliased reference"): it converges as S grows,
// it agrees with the aliased reference inside wide ribbons, and `--reference
// SPEC` gives error.<name> beside error.image or refuses a bad spec (exit 2).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/reference_spec.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using sbtest::runCli;

// A small render with the aa reference at `samples` (light maps of 64 texels:
// 512 at S = 8).
sb::RenderRequest aaRequest(const std::string& backend, const std::string& scene,
                            const std::string& primitive, int samples) {
  sb::RenderRequest r;
  r.scene = scene;
  r.shadow = "exact:size=64";
  r.backend = backend;
  r.width = r.height = 48;
  r.primitive = primitive;
  r.warmup = 0;
  r.reference = true;
  r.references = {"aa:samples=" + std::to_string(samples)};
  return r;
}

sb::Image aaImage(const sb::RenderRequest& r) {
  const sb::RenderResult out = sb::runRender(r);
  EXPECT_EQ(out.moreReferences.size(), 1u);
  EXPECT_EQ(out.moreReferences.at(0).width, r.width * uint32_t(out.moreReferences[0].samples));
  return out.moreReferences.at(0).referenceImage;
}

class AaReference : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    try {
      sb::RenderRequest r = aaRequest(GetParam(), "straight:strands=2,points=3", "lines", 1);
      r.references.clear();
      sb::runRender(r);
    } catch (const sb::DeviceError& e) {
      GTEST_SKIP() << "backend unavailable: " << e.what();
    }
  }
};

TEST_P(AaReference, ConvergesAsSamplesDouble) {
  // The error between S and 2S falls: S = 2 to 4 against 4 to 8, on lines and
  // on ribbons (the ribbons 1.5 pixels wide: neither a whole pixel nor a line).
  for (const auto& [scene, primitive] : std::vector<std::pair<std::string, std::string>>{
           {"curly:strands=60,seed=3,head=0", "lines"},
           {"curly:strands=60,seed=3,head=0", "ribbons"}}) {
    sb::RenderRequest r = aaRequest(GetParam(), scene, primitive, 2);
    if (primitive == "ribbons") r.ribbonWidth = 1.5f;
    const sb::Image s2 = aaImage(r);
    r.references = {"aa:samples=4"};
    const sb::Image s4 = aaImage(r);
    r.references = {"aa:samples=8"};
    const sb::Image s8 = aaImage(r);
    const double e24 = sb::compareImages(s2, s4).rmse, e48 = sb::compareImages(s4, s8).rmse;
    std::cout << "[ measured ] " << GetParam() << " " << primitive << ": RMSE S=2 vs 4 " << e24
              << ", S=4 vs 8 " << e48 << " (ratio " << e48 / e24 << ")\n";
    EXPECT_GT(e24, 0.0) << primitive;
    EXPECT_LT(e48, e24) << primitive;
  }
}

TEST_P(AaReference, AgreesWithTheAliasedReferenceInsideWideRibbons) {
  // Ribbons 10 pixels wide: away from their edges a pixel is covered by the
  // same ribbons at every one of its samples, so the aliased reference (its
  // centre) and the aa reference (the mean of 8 x 8 samples) see the same
  // fragments. Edge pixels are excluded: those whose 3x3 neighbourhood has
  // different eye fragment counts (a ribbon's edge is within a pixel). Compared
  // over the interior pixels a ribbon covers, per pixel its largest channel
  // difference. What is left, and the tolerances (docs/ground-truth.md):
  // - without self-shadowing (shadow_alpha=0): the shading's change across a
  //   pixel (highlights). Measured mean 0.0014, 2 of 114 pixels over 0.05;
  //   required mean <= 0.003 and at most 5% over 0.05.
  // - with it (shadow_alpha=0.5, a 256 light map: 2048 at S = 8): also the
  //   edges of other ribbons' shadows, sharp in the light map, that cross a
  //   pixel inside a ribbon; the aliased reference takes the texel at its
  //   centre, the aa reference 64 samples of 64 texels. They shrink with the
  //   light map (mean 0.031 with a 64 map, 0.0075 with 256). Measured mean
  //   0.0075, 9 of 114 over 0.05; required mean <= 0.015 and at most 15% over.
  for (const char* shadowAlpha : {"0", "0.5"}) {
    const bool shadows = std::string(shadowAlpha) != "0";
    const double kMeanTolerance = shadows ? 0.015 : 0.003, kOverFraction = shadows ? 0.15 : 0.05;
    sb::RenderRequest r = aaRequest(
        GetParam(),
        std::string("straight:strands=8,points=4,seed=5,head=0,shadow_alpha=") + shadowAlpha,
        "ribbons", 8);
    r.ribbonWidth = 10.0f;
    if (shadows) r.shadow = "exact:size=256";
    const sb::RenderResult out = sb::runRender(r);
    ASSERT_EQ(out.moreReferences.size(), 1u);
    ASSERT_TRUE(out.eyeComplexity);
    const sb::Image& aliased = out.referenceImage;
    const sb::Image& aa = out.moreReferences[0].referenceImage;
    const int w = aliased.width, h = aliased.height;
    const std::vector<uint32_t>& counts = out.eyeComplexity->counts;  // bottom-up
    auto count = [&](int x, int y) { return counts[std::size_t(h - 1 - y) * w + x]; };
    // Over the interior pixels a ribbon covers (the background's difference is 0).
    double sum = 0, worst = 0;
    int interior = 0, covered = 0, over = 0;
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        bool edge = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) edge = edge || count(x + dx, y + dy) != count(x, y);
        if (edge) continue;
        ++interior;
        if (count(x, y) == 0) continue;
        ++covered;
        double pixel = 0;
        for (int c = 0; c < 3; ++c) {
          const double d = std::fabs(double(aliased.pixels[aliased.index(x, y, c)]) -
                                     double(aa.pixels[aa.index(x, y, c)]));
          sum += d / 3.0;
          pixel = std::max(pixel, d);
        }
        worst = std::max(worst, pixel);
        over += pixel > 0.05 ? 1 : 0;
      }
    const double mean = sum / covered;
    std::cout << "[ measured ] " << GetParam() << " shadow_alpha " << shadowAlpha << ": "
              << interior << " interior pixels, " << covered
              << " covered by ribbons: mean |aliased - aa| " << mean << ", max " << worst << ", "
              << over << " over 0.05; whole image RMSE " << sb::compareImages(aliased, aa).rmse
              << "\n";
    EXPECT_GT(covered, 80);
    EXPECT_LE(mean, kMeanTolerance);
    EXPECT_LE(double(over) / covered, kOverFraction);
  }
}

TEST_P(AaReference, OneSampleOfRibbonsIsTheAliasedReference) {
  // At S = 1 ribbons are drawn as the aliased reference draws them: the same image.
  sb::RenderRequest r = aaRequest(GetParam(), "curly:strands=60,seed=3", "ribbons", 1);
  r.ribbonWidth = 2.0f;
  const sb::RenderResult out = sb::runRender(r);
  ASSERT_EQ(out.moreReferences.size(), 1u);
  EXPECT_EQ(sb::compareImages(out.referenceImage, out.moreReferences[0].referenceImage).maxAbs,
            0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, AaReference, ::testing::Values("gl", "vulkan"));

TEST(AaReferenceCli, RenderGivesBothErrorsAndRefusesBadSpecs) {
  const auto ok = runCli(
      "render --scene straight:strands=20,points=4 --shadow exact:size=64 --size 32x32 "
      "--warmup 0 --reference --reference aa:samples=4 --json");
  ASSERT_EQ(ok.status, 0) << ok.err;
  const nlohmann::json j = nlohmann::json::parse(ok.out);
  for (const char* key : {"rmse", "psnr", "ssim", "max_abs"}) {
    EXPECT_TRUE(j["error"]["image"].contains(key)) << key;
    EXPECT_TRUE(j["error"]["aa"].contains(key)) << key;
  }
  EXPECT_TRUE(j["error"]["aa"]["flip"].contains("mean"));
  EXPECT_TRUE(j["error"].contains("own"));
  EXPECT_TRUE(j["error"].contains("visibility"));
  EXPECT_EQ(j["error"]["aa"]["reference"]["spec"], "aa:samples=4");
  EXPECT_EQ(j["error"]["aa"]["reference"]["size"], nlohmann::json::array({128, 128}));
  EXPECT_EQ(j["error"]["aa"]["reference"]["light_map_size"], 256);
  EXPECT_GT(j["error"]["aa"]["reference"]["bytes"].get<double>(), 0);
  EXPECT_GT(j["error"]["aa"]["reference"]["wall_ms"].get<double>(), 0);
  // Bad specs: exit 2, the message names the spec and the problem.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"aa:samples=0", "samples"},          {"aa:samples=9", "samples"},
      {"pbrr", "unknown reference 'pbrr'"}, {"aa:size=4", "unknown option 'size'"},
      {"aa:samples=x", "samples"},          {"aa:samples=2 --reference aa:samples=4", "two 'aa'"}};
  for (const auto& [spec, message] : bad) {
    const auto r = runCli("render --scene straight:strands=20,points=4 --size 16x16 --reference " +
                          spec + " --json");
    EXPECT_EQ(r.status, 2) << spec << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << spec << ": " << r.err;
    EXPECT_NE(r.err.find("--reference"), std::string::npos) << spec << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << spec;
  }
  const auto noImage = runCli(
      "render --scene straight:strands=20,points=4 --size 16x16 --no-image --reference "
      "aa:samples=2");
  EXPECT_EQ(noImage.status, 2) << noImage.err;
  EXPECT_NE(noImage.err.find("--no-image"), std::string::npos) << noImage.err;
}

// --reference-out holds the reference asked for: with `--reference aa:samples=2` alone, the
// anti-aliased one (and nothing beside it); with the exact one named too, the exact one there
// and the aa one beside it (the control: the two files differ, and the aa ones are the same).
TEST(AaReferenceCli, ReferenceOutHoldsTheReferenceAskedFor) {
  const auto dir = sbtest::tempDir("ref-out");
  const std::string render =
      "render --scene straight:strands=20,points=4 --shadow exact:size=32 --size 16x16 "
      "--warmup 0 --repeat 1 ";
  const auto aaOnly =
      runCli(render + "--reference aa:samples=2 --reference-out " + (dir / "a.png").string());
  ASSERT_EQ(aaOnly.status, 0) << aaOnly.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "a.png"));
  EXPECT_FALSE(fs::exists(dir / "a.aa.png"));
  EXPECT_FALSE(fs::exists(dir / "a.exact.png"));
  const auto both = runCli(render + "--reference --reference aa:samples=2 --reference-out " +
                           (dir / "b.png").string());
  ASSERT_EQ(both.status, 0) << both.err;
  ASSERT_TRUE(fs::is_regular_file(dir / "b.aa.png"));
  EXPECT_EQ(sbtest::readFile(dir / "a.png"), sbtest::readFile(dir / "b.aa.png"));
  EXPECT_NE(sbtest::readFile(dir / "b.png"), sbtest::readFile(dir / "b.aa.png"));
  fs::remove_all(dir);
}

TEST(AaReferenceCli, ASuiteAsksForItAndTheReportsShowIt) {
  // The suite key "reference" takes the specs; the aa reference is rendered
  // once for the two cases that share scene, view and light map size.
  const fs::path dir = sbtest::tempDir("aa-sweep");
  std::ofstream(dir / "s.json") << R"({
    "name": "aa",
    "defaults": {"scene": "straight:strands=30,points=4,head=0", "size": "24x24", "repeat": 1,
                 "warmup": 0, "backends": ["gl"], "reference": ["exact", "aa:samples=2"]},
    "groups": [{"name": "g", "axes": {"shadow": ["dom:layers=3,size=64", "osm:maps=4,size=64"]}}]
  })";
  const auto run =
      runCli("sweep " + (dir / "s.json").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json doc = nlohmann::json::parse(sbtest::readFile(dir / "out" / "results.json"));
  ASSERT_EQ(doc["results"].size(), 2u);
  int cached = 0;
  for (const auto& r : doc["results"]) {
    EXPECT_TRUE(r["error"]["image"].contains("rmse"));
    EXPECT_TRUE(r["error"]["aa"].contains("rmse"));
    EXPECT_EQ(r["error"]["aa"]["reference"]["spec"], "aa:samples=2");
    cached += r["error"]["aa"]["reference"]["cached"].get<bool>() ? 1 : 0;
  }
  EXPECT_EQ(cached, 1);
  const std::string csv = sbtest::readFile(dir / "out" / "results.csv");
  EXPECT_NE(csv.find(",aa_image_rmse,aa_image_psnr,aa_image_ssim,aa_image_flip_mean,"
                     "aa_reference_spec,aa_reference_wall_ms,aa_reference_bytes\n"),
            std::string::npos)
      << csv.substr(0, csv.find('\n'));
  EXPECT_NE(sbtest::readFile(dir / "out" / "report.md").find("Image RMSE (aa)"), std::string::npos);
  // Its image beside the case's reference: images/<stem>.aa.png, shown in report.html.
  for (const auto& r : doc["results"]) {
    const std::string image = r["images"]["image"];
    EXPECT_EQ(r["images"]["aa"], image.substr(0, image.size() - 4) + ".aa.png");
    EXPECT_TRUE(fs::exists(dir / "out" / r["images"]["aa"].get<std::string>()));
  }
  EXPECT_NE(sbtest::readFile(dir / "out" / "report.html").find("alt=\"aa\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(AaReferenceCli, OverTheBudgetOrTheLargestSideItIsRefused) {
  // A side over 16384 before any work; over the host budget (an address-space
  // limit of 2.2 GB, as tests/test_large_runs.cpp) before its resources are made.
  const auto side = runCli(
      "render --scene straight:strands=20,points=4 --shadow exact:size=64 --size 4096x4096 "
      "--warmup 0 --reference --reference aa:samples=8");
  EXPECT_EQ(side.status, 2) << side.err;
  EXPECT_NE(side.err.find("32768x32768 samples"), std::string::npos) << side.err;
  if (sbtest::kAsan) GTEST_SKIP() << sbtest::kNoLimitUnderAsan;
  const fs::path dir = sbtest::tempDir("aa-budget");
  const std::string cmd =
      "(ulimit -v 2200000 && exec " SB_CLI
      " render --scene straight:strands=200,points=8 --shadow exact:size=1024 --size 256x256 "
      "--warmup 0 --reference --reference aa:samples=8 --out " +
      (dir / "x.png").string() + ") >/dev/null 2>" + (dir / "err").string();
  const int raw = std::system(cmd.c_str());
  const std::string err = sbtest::readFile(dir / "err");
  EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 2) << err;
  EXPECT_NE(err.find("the anti-aliased reference (aa:samples=8"), std::string::npos) << err;
  EXPECT_NE(err.find("over the device's budget"), std::string::npos) << err;
  EXPECT_NE(err.find("fewer samples="), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
  fs::remove_all(dir);
}

TEST(AaReferenceCli, SpecsParseAsTechniqueSpecs) {
  EXPECT_EQ(sb::parseReferenceSpec("aa").str(), "aa:samples=4");  // the default
  EXPECT_EQ(sb::parseReferenceSpec("aa:samples=8").str(), "aa:samples=8");
  EXPECT_EQ(sb::parseReferenceSpec("exact").str(), "exact");
  EXPECT_THROW(sb::parseReferenceSpec("exact:samples=2"), sb::InputError);
  EXPECT_THROW(sb::parseReferenceSpec("aa:samples=4,samples=2"), sb::InputError);
}

}  // namespace
