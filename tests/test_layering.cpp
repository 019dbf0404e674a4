// The layers point one way: the build runs cmake/CheckIncludes.cmake over backends/, scenes/,
// reports/ and render/ (CMakeLists.txt, sb_check_includes), so a build with an
// include against the layering fails. Here the check itself is shown passing and failing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util.h"

namespace {

namespace fs = std::filesystem;

int runCheck(const fs::path& dir, const std::string& allowed, std::string& output) {
  const fs::path out = dir / "check.txt";
  const std::string cmd = "cmake -DDIR=" + dir.string() + " '-DALLOWED=" + allowed +
                          "' -DSTAMP=" + (dir / "ok").string() + " -P " + SB_SOURCE_DIR +
                          "/cmake/CheckIncludes.cmake >" + out.string() + " 2>&1";
  const int raw = std::system(cmd.c_str());
  output = sbtest::readFile(out);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(Layering, AnIncludeAgainstTheLayersFailsTheCheck) {
  const fs::path dir = sbtest::tempDir("layering");
  fs::create_directories(dir / "gl");
  std::ofstream(dir / "gl" / "device.cpp") << "#include \"backends/device.h\"\n#include <vector>\n";
  std::string output;
  EXPECT_EQ(runCheck(dir, "backends/|base/", output), 0) << output;
  EXPECT_TRUE(fs::exists(dir / "ok"));
  // One folder down, as backends/gl/ is: the check looks into subfolders.
  std::ofstream(dir / "gl" / "device.cpp", std::ios::app) << "#include \"harness/render.h\"\n";
  fs::remove(dir / "ok");
  EXPECT_NE(runCheck(dir, "backends/|base/", output), 0);
  EXPECT_NE(output.find("harness/render.h"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(dir / "ok"));
  fs::remove_all(dir);
}

}  // namespace
