// The CI guard of tests/main.cpp: a test that skips because its backend is missing fails
// under CI=true and skips otherwise. Shown on a child run of this binary with Vulkan's driver
// hidden (an ICD file that does not exist).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "test_util.h"

namespace {

sbtest::CliResult runSelfWithoutVulkan(const std::string& ci) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const auto dir = sbtest::tempDir("ciguard");
  // SB_SKIP_LOG emptied: the child's skip is not one of this run's.
  const std::string cmd =
      "CI=" + ci + " SB_SKIP_LOG= VK_ICD_FILENAMES=" + (dir / "none.json").string() +
      " VK_DRIVER_FILES=" + (dir / "none.json").string() + " " + self +
      " --gtest_filter=Backends/PaperDefinitions.DomFirstPassIsDepthOnly/vulkan >" +
      (dir / "out").string() + " 2>&1";
  sbtest::CliResult r;
  const int raw = std::system(cmd.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = sbtest::readFile(dir / "out");
  std::filesystem::remove_all(dir);
  return r;
}

TEST(CiGuard, MissingBackendFailsUnderCi) {
  const sbtest::CliResult r = runSelfWithoutVulkan("true");
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("CI=true: this test may not skip"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("backend unavailable: no Vulkan device"), std::string::npos) << r.out;
}

// The exit status is not this test's: the process's global check that Vulkan printed no
// validation message fails on the loader's own complaint about the missing driver.
TEST(CiGuard, MissingBackendSkipsOutsideCi) {
  const sbtest::CliResult r = runSelfWithoutVulkan("false");
  EXPECT_NE(r.out.find("[  SKIPPED ] Backends/PaperDefinitions"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("CI=true: this test may not skip"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("backend unavailable: no Vulkan device"), std::string::npos) << r.out;
}

}  // namespace
