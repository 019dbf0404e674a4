// Memory known before it is spent: a run's resources follow from the culled
// graph's pass declarations, so `render` knows their bytes before the first
// frame (memory.estimated_bytes) and can refuse a run over --memory-limit
// before making them.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "harness/render.h"
#include "techniques/common/unit.h"
#include "test_util.h"

namespace sb {
namespace {

namespace fs = std::filesystem;

std::size_t allocated(const RenderResult& r) {
  std::size_t total = 0;
  for (const auto& x : r.resources) total += x.bytes;
  return total;
}

RenderRequest small(const std::string& shadow, const std::string& oit) {
  RenderRequest req;
  req.scene = "straight:strands=40,points=6,head=1,alpha=0.5";
  req.shadow = shadow;
  req.oit = oit;
  req.width = req.height = 24;
  req.repeat = 1;
  req.warmup = 0;
  return req;
}

TEST(MemoryPlan, TheEstimateIsWhatEveryTechniqueAllocates) {
  std::vector<RenderRequest> runs;
  for (const auto* t : techniques(Family::Shadow)) runs.push_back(small(t->name, "none"));
  for (const auto* t : techniques(Family::Transparency)) runs.push_back(small("dom", t->name));
  RenderRequest visibilityOnly = small("occupancy", "none");
  visibilityOnly.reference = true;
  visibilityOnly.image = false;
  runs.push_back(visibilityOnly);
  RenderRequest vulkan = small("osm", "abuffer");
  vulkan.backend = "vulkan";
  runs.push_back(vulkan);
  for (const auto& req : runs) {
    SCOPED_TRACE(req.backend + " " + req.shadow + " + " + req.oit);
    const RenderResult r = runRender(req);
    EXPECT_GT(r.estimatedBytes, 0u);
    EXPECT_EQ(r.estimatedBytes, allocated(r));
  }
}

TEST(MemoryPlan, ARunOverTheLimitIsRefusedWithItsLargestResources) {
  const fs::path dir = sbtest::tempDir("memory-limit");
  const std::string base =
      "render --scene straight:strands=40,points=6,head=0 --shadow osm:maps=16 --size 32x32 "
      "--repeat 1 --warmup 0 --json --out " +
      (dir / "image.png").string();
  // The estimate of the same run, then the limit one byte under and at it.
  const sbtest::CliResult ok = sbtest::runCli(base);
  ASSERT_EQ(ok.status, 0) << ok.err;
  const auto estimate = nlohmann::json::parse(ok.out)["memory"]["estimated_bytes"].get<long long>();
  fs::remove(dir / "image.png");

  const sbtest::CliResult over =
      sbtest::runCli(base + " --memory-limit " + std::to_string(estimate - 1));
  EXPECT_EQ(over.status, 2);
  EXPECT_NE(over.err.find("memory limit"), std::string::npos) << over.err;
  EXPECT_NE(over.err.find("osm.maps (shadow)"), std::string::npos) << over.err;
  EXPECT_FALSE(fs::exists(dir / "image.png"));
  // Refused before they were made: what the device had made by then (the
  // scene, the counting passes) leaves out the maps.
  std::size_t maps = 0;
  const nlohmann::json okReport = nlohmann::json::parse(ok.out);
  for (const auto& r : okReport["memory"]["resources"])
    if (r["name"] == "osm.maps") maps = r["bytes"].get<std::size_t>();
  ASSERT_GT(maps, 0u);
  std::smatch made;
  const std::string err = over.err;
  ASSERT_TRUE(std::regex_search(err, made, std::regex("made so far: ([0-9]+) bytes"))) << err;
  EXPECT_LE(std::stoull(made[1]) + maps, static_cast<unsigned long long>(estimate)) << err;

  const sbtest::CliResult at = sbtest::runCli(base + " --memory-limit " + std::to_string(estimate));
  EXPECT_EQ(at.status, 0) << at.err;
  EXPECT_TRUE(fs::exists(dir / "image.png"));
}

}  // namespace
}  // namespace sb
