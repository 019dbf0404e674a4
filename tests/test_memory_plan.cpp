// Memory known before it is spent: a run's resources follow from the culled
// graph's pass declarations, so `render` knows their bytes before the first
// frame (memory.estimated_bytes) and can refuse a run over --memory-limit
// before making them.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>

#include "harness/render.h"
#include "render/common/unit.h"
#include "render_request.h"
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
  return sbtest::smallRender(RenderRequest{}.backend,
                             "straight:strands=40,points=6,head=1,alpha=0.5", shadow, oit, 24);
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

// The whole plan is put to the limit before anything is made, the scene's own
// buffers included: the refusal names the plan's total (the run's estimate:
// an osm run declares every resource up front), the owner that takes most of
// it, and the true factor over the limit. It used to refuse at the scene's
// buffers with "1.0x less memory" and name no map.
TEST(MemoryPlan, ARefusalNamesTheWholePlansTotalAndATrueFactor) {
  const std::string base =
      "render --scene straight:strands=2000 --shadow osm:maps=64 --size 128x128 --repeat 1 "
      "--warmup 0 --json";
  const sbtest::CliResult ok = sbtest::runCli(base);
  ASSERT_EQ(ok.status, 0) << ok.err;
  const auto estimate = nlohmann::json::parse(ok.out)["memory"]["estimated_bytes"].get<long long>();
  const long long limit = 1000000;
  ASSERT_GT(estimate, 10 * limit);
  const sbtest::CliResult over = sbtest::runCli(base + " --memory-limit " + std::to_string(limit));
  EXPECT_EQ(over.status, 2);
  const std::string err = over.err;
  EXPECT_NE(err.find("needs " + std::to_string(estimate) + " bytes"), std::string::npos) << err;
  EXPECT_NE(err.find("made so far: 0 bytes"), std::string::npos) << err;
  EXPECT_NE(err.find("osm.maps (shadow)"), std::string::npos) << err;
  EXPECT_NE(err.find("By owner: shadow"), std::string::npos) << err;  // the largest first
  char factor[32];
  std::snprintf(factor, sizeof factor, "(%.1fx less memory", double(estimate) / double(limit));
  EXPECT_NE(err.find(factor), std::string::npos) << factor << " in " << err;
  // Advice for the owner that takes most, and none for what cannot help.
  EXPECT_NE(err.find("the shadow technique's maps"), std::string::npos) << err;
  EXPECT_EQ(err.find("the scene: fewer strands"), std::string::npos) << err;
  // Control: a limit the plan fits runs.
  const sbtest::CliResult at = sbtest::runCli(base + " --memory-limit " + std::to_string(estimate));
  EXPECT_EQ(at.status, 0) << at.err;
}

// A fragment pool larger than one storage binding is split into pages
// (abuffer.glsl). Forced by SB_POOL_PAGE_BYTES (pages of about half the pool),
// a small scene's pool splits, and the image is the unsplit one, pixel for
// pixel, on both APIs, for every technique on those lists; a pool that needs
// more pages than are bound is refused, naming its size.
TEST(MemoryPlan, AFragmentPoolSplitIntoPagesGivesTheSameImage) {
  auto bytesOf = [](const RenderResult& r, const std::string& name) {
    for (const auto& x : r.resources)
      if (x.name == name) return x.bytes;
    return std::size_t{0};
  };
  const std::string scene = "straight:strands=40,points=6,head=1,alpha=0.5";
  for (const std::string backend : {"gl", "vulkan"}) {
    for (const std::string oit : {"abuffer", "kbuffer", "mlab"}) {
      SCOPED_TRACE(backend + " " + oit);
      // Shadow maps: the hook pages exact's node pool too (tests/test_exact_paging.cpp).
      const RenderRequest req = sbtest::smallRender(backend, scene, "shadowmap", oit, 24);
      const RenderResult whole = runRender(req);
      const std::size_t bytes = bytesOf(whole, oit + ".fragments");
      ASSERT_GT(bytes, 32u * 16);
      const std::size_t page = 32 * std::bit_floor(bytes / 32 / 2);
      ::setenv("SB_POOL_PAGE_BYTES", std::to_string(page).c_str(), 1);
      const RenderResult split = runRender(req);
      ::unsetenv("SB_POOL_PAGE_BYTES");
      // It split: the first page is full, the second holds the next entries.
      EXPECT_EQ(bytesOf(split, oit + ".fragments"), page);
      EXPECT_GT(bytesOf(split, oit + ".fragments.page1"), 32u);
      std::size_t pages = 0;
      for (const auto& x : split.resources)
        if (x.name.rfind(oit + ".fragments", 0) == 0) pages += x.bytes;
      EXPECT_GE(pages, bytes);  // the pages unused hold 32 bytes each
      EXPECT_LE(pages, bytes + 4 * 32);
      EXPECT_EQ(split.warnings, whole.warnings);
      ASSERT_FALSE(whole.image.pixels.empty());
      EXPECT_TRUE(split.image.pixels == whole.image.pixels);
    }
  }
  // Control: the comparison sees another technique's image as different.
  const RenderResult abuffer = runRender(sbtest::smallRender("gl", scene, "exact", "abuffer", 24));
  const RenderResult k1 = runRender(sbtest::smallRender("gl", scene, "exact", "kbuffer:k=1", 24));
  EXPECT_FALSE(abuffer.image.pixels == k1.image.pixels);
  // One entry a page: more pages than are bound.
  ::setenv("SB_POOL_PAGE_BYTES", "32", 1);
  try {
    runRender(sbtest::smallRender("vulkan", scene, "none", "abuffer", 24));
    ADD_FAILURE() << "a pool over every page bound ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("abuffer: the fragment pool"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("storage bindings of at most 32 bytes"), std::string::npos)
        << e.what();
  }
  ::unsetenv("SB_POOL_PAGE_BYTES");
}

// The limit holds from the first resource on: a run whose light maps alone
// pass it (exact:size=16384: four 1 GiB maps, counted by a preparation that
// runs before the frames' plan) is refused before the counting pass makes
// them. It used to run 30 s and peak at 5.5 GB resident, then say "refused
// before they were made (made so far: 4345851608 bytes)".
TEST(MemoryPlan, TheLimitHoldsBeforeThePreparationsCountingPass) {
  const fs::path dir = sbtest::tempDir("memory-limit-prepare");
  const long long limit = 2000000000;
  const std::string out = (dir / "image.png").string(), err = (dir / "err").string();
  std::vector<std::string> args = {SB_CLI,           "render",
                                   "--size",         "256x256",
                                   "--shadow",       "exact:size=16384",
                                   "--oit",          "abuffer",
                                   "--memory-limit", std::to_string(limit),
                                   "--out",          out};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, SB_CLI, &files, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&files);
  int status = 0;
  rusage usage{};
  ASSERT_EQ(wait4(pid, &status, 0, &usage), pid);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string message = sbtest::readFile(err);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2) << message;
  EXPECT_NE(message.find("over the memory limit"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(out));
  // What was made before the refusal is within the limit (the message says so).
  std::smatch made;
  ASSERT_TRUE(std::regex_search(message, made, std::regex("made so far: ([0-9]+) bytes")))
      << message;
  EXPECT_LE(std::stoll(made[1]), limit) << message;
  // Peak resident memory (ru_maxrss, KiB): under the limit plus a margin of
  // 512 MiB for the process itself (libraries, drivers, the scene; about
  // 210 MiB measured).
  const long long peak = static_cast<long long>(usage.ru_maxrss) * 1024;
  const long long margin = 512ll << 20;
  std::cout << "[ memory limit ] refused in " << seconds << " s, peak resident " << peak / (1 << 20)
            << " MiB (limit " << limit / (1 << 20) << " MiB + margin " << margin / (1 << 20)
            << " MiB)\n";
  EXPECT_LE(peak, limit + margin);
  EXPECT_LT(seconds, 20.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sb
