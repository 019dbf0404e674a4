// The viewer frees what a technique made when it switches (a renderer's
// resources and pipelines go with it): after 50 switches on a tiny scene the
// device holds what a fresh headless run of the final settings holds, and the
// process's resident memory is within 10% of what it was after one warm cycle
// through every technique (the caches of the drivers filled), on GL and on
// Vulkan.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "render/common/technique.h"
#include "render/common/unit.h"
#include "tests/test_util.h"
#include "tests/window_test_util.h"

namespace fs = std::filesystem;

namespace {

class ViewMemoryTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!sbtest::haveDisplay()) GTEST_SKIP() << sbtest::kNoDisplay;
  }
};

nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(sbtest::readFile(p)); }

TEST_P(ViewMemoryTest, FiftyTechniqueSwitchesLeaveWhatAFreshRunHolds) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = sbtest::tempDir("view-memory");
  const std::size_t shadows = sb::techniques(sb::Family::Shadow).size(),
                    oits = sb::techniques(sb::Family::Transparency).size();
  constexpr std::size_t kSwitches = 50;
  ASSERT_LT(shadows + oits, kSwitches);
  // One warm cycle through every technique of both families (back to the
  // first), then the rest of the 50 switches back and forth.
  std::ofstream script(dir / "session.txt");
  for (std::size_t i = 0; i < oits; ++i) script << "0 key T\n";
  for (std::size_t i = 0; i < shadows; ++i) script << "0 key S\n";
  script << "0 screenshot warm\n";
  for (std::size_t i = shadows + oits; i < kSwitches; ++i)
    script << (i % 2 ? "0 key T shift\n" : "0 key S\n");
  script << "0 screenshot last\n0 quit\n";
  script.close();
  const std::string scene = "curly:strands=40,points=6,seed=5,alpha=0.4";
  const std::string backend = GetParam();
  const sbtest::CliResult r = sbtest::runCli(
      "view --backend " + backend + " --scene " + scene +
      " --shadow shadowmap --oit wsum --size 32x32 --script " + (dir / "session.txt").string() +
      " --screenshot-dir " + (dir / "shots").string());
  ASSERT_EQ(r.status, 0) << r.err << r.out;

  const nlohmann::json warm = readJson(dir / "shots" / "warm.json");
  const nlohmann::json last = readJson(dir / "shots" / "last.json");
  // The device's accounting: what a fresh headless run of the final settings holds.
  std::vector<std::string> args = last.at("render_args").get<std::vector<std::string>>();
  ASSERT_EQ(args[args.size() - 2], "--out");
  args.back() = (dir / "again.png").string();
  std::string cmd;
  for (std::size_t i = 1; i < args.size(); ++i) cmd += "'" + args[i] + "' ";
  const sbtest::CliResult fresh = sbtest::runCli(cmd + "--json");
  ASSERT_EQ(fresh.status, 0) << cmd << "\n" << fresh.err;
  const nlohmann::json freshMemory = nlohmann::json::parse(fresh.out).at("memory");
  EXPECT_EQ(last.at("report").at("memory").at("resources"), freshMemory.at("resources"))
      << "viewer after " << kSwitches << " switches vs " << cmd;
  EXPECT_EQ(last.at("report").at("memory").at("total_bytes"), freshMemory.at("total_bytes"));

  const double warmBytes = warm.at("resident_bytes").get<double>();
  const double lastBytes = last.at("resident_bytes").get<double>();
  ASSERT_GT(warmBytes, 0.0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ view memory ] " << backend << ": resident " << warmBytes / (1 << 20)
            << " MiB after the warm cycle (" << shadows + oits << " switches), "
            << lastBytes / (1 << 20) << " MiB after " << kSwitches << "; device "
            << freshMemory.at("total_bytes") << " bytes; " << seconds << " s\n";
  // Both APIs. The Vulkan growth (1.3 MiB a rebuild, 4-5 MiB a switch to an
  // unseen pair) was lavapipe's leak of the shader variants it inlines uniform
  // buffer values into, gone with uniforms read as storage buffers there
  // (VulkanPlatform::uniformsAsStorage), and freed memory glibc kept, given
  // back after each renderer's group (Device::destroyGroup). Measured on a
  // session like this one: Vulkan 352 -> 433 MiB before, 226 -> 231 MiB
  // after; GL 218 -> 220-230 MiB.
  // Under AddressSanitizer freed memory waits in its quarantine (up to 256 MiB) before it is
  // reused, so resident memory grows with every free: the device accounting above still
  // holds, the resident bound does not mean anything there.
  if (!sbtest::kAsan) {
    EXPECT_LE(lastBytes, warmBytes * 1.10);
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewMemoryTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
