// --msaa N, the scene-wide anti-aliasing: the techniques that render into multisampled frame
// targets (opaque hair, the blended wsum, wavg, wboit, fake transparency) give the same image on GL
// and Vulkan, change only the pixels anti-aliasing changes (edges: the image differs from --msaa 1,
// but little on average), and count every sample in their memory; the techniques that keep
// per-pixel data refuse it with an input error, as does a count the device lacks.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "render/common/unit.h"
#include "test_util.h"

namespace {

using namespace sbtest;
using json = nlohmann::json;
namespace fs = std::filesystem;

// Ribbons over the head: triangles, whose edges anti-aliasing smooths.
const std::string kArgs =
    "render --scene straight:strands=300,points=8,alpha=0.4 --primitive ribbons --size 48x48 "
    "--warmup 0 --json";

json renderJson(const std::string& args) {
  const CliResult r = runCli(kArgs + " " + args);
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  return json::parse(r.out.substr(r.out.find('{')));
}

json compare(const fs::path& a, const fs::path& b) {
  const CliResult r = runCli("compare " + a.string() + " " + b.string());
  return json::parse(r.out.substr(r.out.find('{')));
}

TEST(Msaa, MultisampledTechniquesAntiAliasTheSameOnBothApis) {
  const fs::path dir = tempDir("msaa");
  for (const std::string oit : {"none", "wsum", "wavg", "wboit"}) {
    SCOPED_TRACE(oit);
    std::map<std::string, fs::path> png;
    std::map<std::string, json> out;
    for (const std::string backend : {"gl", "vulkan"})
      for (const int n : {1, 4}) {
        const std::string key = backend + std::to_string(n);
        png[key] = dir / (oit + "-" + key + ".png");
        out[key] = renderJson("--oit " + oit + " --backend " + backend + " --msaa " +
                              std::to_string(n) + " --out " + png[key].string());
      }
    // The two APIs agree with and without anti-aliasing.
    EXPECT_LE(compare(png["gl4"], png["vulkan4"])["max_abs"].get<double>(), 1e-3);
    EXPECT_LE(compare(png["gl1"], png["vulkan1"])["max_abs"].get<double>(), 1e-3);
    // Anti-aliasing changes the edges (some pixels by more than a level) and little else.
    const json d = compare(png["gl1"], png["gl4"]);
    EXPECT_GT(d["pixels_over"].get<int>(), 10) << "4 samples changed no edge";
    EXPECT_LT(d["rmse"].get<double>(), 0.06);
    // Memory: the blended techniques' targets have 4 samples plus the averaged copy.
    const double one = out["gl1"]["memory"]["oit_bytes"].get<double>();
    EXPECT_EQ(out["gl4"]["memory"]["oit_bytes"].get<double>(), 5 * one);
  }
  fs::remove_all(dir);
}

// Fake transparency's three opaque subsets draw into N-sample images, averaged before its
// blend (premultiplied, so the averages are coverage and colour), and the blend runs per sample
// over the multisampled opaque colour: the same on both APIs, the edges anti-aliased, every
// sample counted (3 RGBA32F images and the subsets' depth, N samples each, plus the averages).
TEST(Msaa, FakeTransparencyAntiAliasesTheSameOnBothApis) {
  const fs::path dir = tempDir("msaa-fake");
  std::map<std::string, fs::path> png;
  std::map<std::string, json> out;
  for (const std::string backend : {"gl", "vulkan"})
    for (const int n : {1, 4}) {
      const std::string key = backend + std::to_string(n);
      png[key] = dir / ("fake-" + key + ".png");
      out[key] = renderJson("--oit fake --backend " + backend + " --msaa " + std::to_string(n) +
                            " --out " + png[key].string());
    }
  EXPECT_LE(compare(png["gl4"], png["vulkan4"])["max_abs"].get<double>(), 1e-3);
  EXPECT_LE(compare(png["gl1"], png["vulkan1"])["max_abs"].get<double>(), 1e-3);
  const json d = compare(png["gl1"], png["gl4"]);
  EXPECT_GT(d["pixels_over"].get<int>(), 10) << "4 samples changed no edge";
  EXPECT_LT(d["rmse"].get<double>(), 0.06);  // measured 0.0188
  const double pixels = 48.0 * 48.0;
  EXPECT_EQ(out["gl4"]["memory"]["oit_bytes"].get<double>() -
                out["gl1"]["memory"]["oit_bytes"].get<double>(),
            pixels * (3 * 4 * 16 + 3 * 4));
  fs::remove_all(dir);
}

TEST(Msaa, PerPixelTechniquesAndMissingCountsAreRefused) {
  for (const std::string oit : {"abuffer", "peel", "occupancy", "kbuffer"}) {
    const CliResult r = runCli(kArgs + " --oit " + oit + " --msaa 4");
    EXPECT_EQ(r.status, 2) << oit;
    EXPECT_NE(r.err.find("'" + oit + "'"), std::string::npos) << r.err;
  }
  const CliResult bad = runCli(kArgs + " --msaa 3");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("msaa"), std::string::npos) << bad.err;
}

// Every registered transparency technique, from the registry: either it renders with --msaa 4,
// or it states why not in its descriptor (Capabilities::msaaRefusal) and the refusal prints it.
TEST(Msaa, EveryTransparencyTakesItOrSaysWhyNot) {
  for (const sb::TechniqueDescriptor* d : sb::techniques(sb::Family::Transparency)) {
    SCOPED_TRACE(d->name);
    const CliResult r = runCli(kArgs + " --oit " + d->name + " --msaa 4");
    if (d->caps.multisampling) {
      EXPECT_TRUE(d->caps.msaaRefusal.empty()) << "multisampled, yet states a refusal";
      EXPECT_EQ(r.status, 0) << r.err;
      continue;
    }
    EXPECT_FALSE(d->caps.msaaRefusal.empty()) << "refuses --msaa without a stated reason";
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("'" + d->name + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(d->caps.msaaRefusal), std::string::npos) << r.err;
  }
}

}  // namespace
