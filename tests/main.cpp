// The test binary's main: GoogleTest, plus two things every test gets.
//  - Under CI=true, a test skipped because the machine lacks what the test command sets up (a
//    backend, a display, Chromium) fails instead: a broken Mesa would otherwise turn half the
//    suite into skips with ctest still green. Skips for a missing device capability (a GPU-only
//    timer path, say) stay skips: their messages name no such cause.
//  - With SB_SKIP_LOG=DIR, each skip is written to DIR (one file per process, a line per skip:
//    reason, tab, test), which scripts/test.sh counts by reason.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace {

bool inCi() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

// The skip messages that mean "this machine was not set up", as the tests word them
// (tests/gpu_test_util.h, tests/window_test_util.h, tests/browser_util.h and their callers).
bool setUpMissing(const std::string& message) {
  for (const char* cause : {"backend unavailable", "no backend", "no display", "is not installed"})
    if (message.find(cause) != std::string::npos) return true;
  return false;
}

// The reason of a skip: its message's first line without GoogleTest's "Skipped" prefix.
std::string reasonOf(const testing::TestPartResult& r) {
  std::string m = r.message() ? r.message() : "";
  if (m.rfind("Skipped\n", 0) == 0) m.erase(0, 8);
  if (const auto nl = m.find('\n'); nl != std::string::npos) m.erase(nl);
  return m.empty() ? "(no reason given)" : m;
}

class SkipPolicy : public testing::EmptyTestEventListener {
 public:
  SkipPolicy() {
    if (const char* dir = std::getenv("SB_SKIP_LOG"); dir && *dir) {
      std::filesystem::create_directories(dir);
      logPath_ = std::string(dir) + "/" + std::to_string(::getpid()) + ".txt";
    }
  }
  // GoogleTest holds its lock while it reports a part result: anything that asks it for
  // state (the current test, a failure) waits for OnTestEnd.
  void OnTestPartResult(const testing::TestPartResult& r) override {
    if (!r.skipped()) return;
    skip_ = reasonOf(r);
    skipAt_ = {r.file_name() ? r.file_name() : "?", r.line_number()};
  }
  // Before the result printer (main() orders them), so a failure is reported as one.
  void OnTestEnd(const testing::TestInfo& test) override {
    if (skip_.empty()) return;
    const std::string reason = std::exchange(skip_, "");
    if (inCi() && setUpMissing(reason)) {
      ADD_FAILURE_AT(skipAt_.first.c_str(), skipAt_.second)
          << "CI=true: this test may not skip for a missing set-up (" << reason
          << "); the test command installs and configures what it needs";
      return;
    }
    if (!logPath_.empty())
      std::ofstream(logPath_, std::ios::app)
          << reason << '\t' << test.test_suite_name() << "." << test.name() << '\n';
  }

 private:
  std::string logPath_;
  std::string skip_;  // the running test's skip reason, if it skipped
  std::pair<std::string, int> skipAt_;
};

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  testing::TestEventListeners& listeners = testing::UnitTest::GetInstance()->listeners();
  testing::TestEventListener* printer = listeners.Release(listeners.default_result_printer());
  listeners.Append(new SkipPolicy);
  listeners.Append(printer);
  return RUN_ALL_TESTS();
}
