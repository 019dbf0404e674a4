// Helpers shared by the tests: running the CLI, temporary folders, expected errors.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sbtest {

// Runs f, expects an sb::InputError whose message contains every given substring.
inline void expectInputError(const std::function<void()>& f, std::vector<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown (expected one mentioning '" << needles[0] << "')";
  } catch (const sb::InputError& e) {
    const std::string msg = e.what();
    for (const std::string& n : needles) {
      EXPECT_NE(msg.find(n), std::string::npos) << "message: " << msg << "\nlacks: " << n;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

// Strand arrays agree with each other and every point is finite.
inline void expectWellFormed(const sb::Strands& s) {
  ASSERT_EQ(s.firstPoint.size(), s.pointCount.size());
  ASSERT_EQ(s.colors.size(), s.points.size());
  ASSERT_EQ(s.thickness.size(), s.points.size());
  ASSERT_EQ(s.transparency.size(), s.points.size());
  uint64_t next = 0;
  for (std::size_t i = 0; i < s.strandCount(); ++i) {
    ASSERT_EQ(s.firstPoint[i], next);
    next += s.pointCount[i];
  }
  ASSERT_EQ(next, s.points.size());
  for (const glm::vec3& p : s.points) {
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
}

struct CliResult {
  int status = -1;
  std::string out, err;
};

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// A fresh temporary folder per call.
inline std::filesystem::path tempDir(const std::string& tag) {
  std::random_device rd;
  auto dir =
      std::filesystem::temp_directory_path() / ("strandbench-" + tag + "-" + std::to_string(rd()));
  std::filesystem::create_directories(dir);
  return dir;
}

// args are passed through the shell; quote them where needed. env: "NAME=value ..." set
// for this command only.
inline CliResult runCli(const std::string& args, const std::string& env = "") {
  const auto dir = tempDir("cli");
  const std::string cmd = (env.empty() ? "" : "env " + env + " ") + std::string(SB_CLI) + " " +
                          args + " >" + (dir / "out").string() + " 2>" + (dir / "err").string();
  CliResult r;
  const int raw = std::system(cmd.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = readFile(dir / "out");
  r.err = readFile(dir / "err");
  std::filesystem::remove_all(dir);
  return r;
}

// Why drivers/mesa-25.0 (Mesa 25.0.7 beside the system's) cannot be used, or "". CI runs
// scripts/setup.sh --tests, which fetches it: "is not installed" makes the skip a failure
// there (tests/main.cpp).
inline std::string mesa25Missing() {
  if (std::filesystem::exists(std::filesystem::path(SB_SOURCE_DIR) / "drivers/mesa-25.0/complete"))
    return "";
  return "drivers/mesa-25.0 is not installed (scripts/drivers.sh fetches it; scripts/setup.sh "
         "--tests runs it)";
}

// AddressSanitizer reserves terabytes of address space for its shadow memory as a
// process starts, which `ulimit -v` refuses: under the sanitizer build
// (scripts/test-sanitizers.sh) the CLI cannot start under an address-space limit.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif
inline constexpr const char* kNoLimitUnderAsan =
    "AddressSanitizer cannot reserve its shadow memory under an address-space limit (ulimit -v)";

}  // namespace sbtest
