// The CI guard of tests/main.cpp: a test that skips because its backend is missing fails
// under CI=true and skips otherwise. Shown on a child run of this binary with Vulkan's driver
// hidden (an ICD file that does not exist).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "test_util.h"

namespace {

// The child's skips are logged to its own folder (SB_SKIP_LOG), not to this run's; the log's
// lines come back in `err`.
sbtest::CliResult runSelfWithoutVulkan(const std::string& ci) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const auto dir = sbtest::tempDir("ciguard");
  const std::string cmd =
      "CI=" + ci + " SB_SKIP_LOG=" + (dir / "skips").string() +
      " VK_ICD_FILENAMES=" + (dir / "none.json").string() +
      " VK_DRIVER_FILES=" + (dir / "none.json").string() + " " + self +
      " --gtest_filter=Backends/PaperDefinitions.DomFirstPassIsDepthOnly/vulkan >" +
      (dir / "out").string() + " 2>&1";
  sbtest::CliResult r;
  const int raw = std::system(cmd.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = sbtest::readFile(dir / "out");
  if (std::filesystem::is_directory(dir / "skips"))
    for (const auto& f : std::filesystem::directory_iterator(dir / "skips"))
      r.err += sbtest::readFile(f.path());
  std::filesystem::remove_all(dir);
  return r;
}

TEST(CiGuard, MissingBackendFailsUnderCi) {
  const sbtest::CliResult r = runSelfWithoutVulkan("true");
  EXPECT_EQ(r.err, "") << "a failure is not a skip";
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
  // The skip is logged with its reason and test, as scripts/test-report.sh counts them.
  EXPECT_NE(r.err.find("backend unavailable: no Vulkan device"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\tBackends/PaperDefinitions.DomFirstPassIsDepthOnly/vulkan"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("backend unavailable: no Vulkan device"), std::string::npos) << r.out;
}

}  // namespace
