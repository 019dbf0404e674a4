// Headless Chromium for tests that check a page loads offline, logs nothing to
// the console and renders something.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "imaging/image.h"
#include "test_util.h"

namespace sbtest {

inline constexpr const char* kChromium = "/usr/bin/chromium";

// Console messages in Chromium's stderr log (--enable-logging=stderr). Every
// message a page produces (console.*, an uncaught exception, a blocked load under
// the page's Content-Security-Policy) is one line
//   [pid:tid:time:INFO:CONSOLE:1] "Uncaught ReferenceError: f is not defined", source: URL (1)
// (older versions write CONSOLE(1)). Chromium logs web pages' messages at INFO
// whatever their level, so a page with no scripts must log none at all.
inline std::vector<std::string> consoleMessages(const std::string& log) {
  std::vector<std::string> messages;
  std::size_t start = 0;
  while (start < log.size()) {
    std::size_t end = log.find('\n', start);
    if (end == std::string::npos) end = log.size();
    const std::string line = log.substr(start, end - start);
    const std::size_t tag = line.find(":CONSOLE");
    const std::size_t close = line.find("] ", tag == std::string::npos ? 0 : tag);
    if (line.starts_with("[") && tag != std::string::npos && close != std::string::npos)
      messages.push_back(line.substr(close + 2));
    start = end + 1;
  }
  return messages;
}

struct PageLoad {
  int status = -1;
  std::string dom;  // the DOM after loading (--dump-dom)
  std::string log;  // Chromium's stderr
  std::vector<std::string> console;
  std::filesystem::path screenshot;
};

// Loads `html` from file:// in headless Chromium (no GPU, no sandbox: it runs as
// root in containers), 2 s of virtual time, one run for both the screenshot and
// the DOM; `work` holds the profile, screenshot and logs.
inline PageLoad loadPage(const std::filesystem::path& html, const std::filesystem::path& work) {
  std::filesystem::create_directories(work);
  PageLoad p;
  p.screenshot = work / "screenshot.png";
  const std::string cmd =
      std::string("timeout 60 ") + kChromium +
      " --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run"
      " --disable-extensions --user-data-dir='" +
      (work / "profile").string() + "' --enable-logging=stderr --v=0 --screenshot='" +
      p.screenshot.string() +
      "' --dump-dom --window-size=1280,2000 --virtual-time-budget=2000 'file://" +
      std::filesystem::absolute(html).string() + "' >'" + (work / "dom.html").string() + "' 2>'" +
      (work / "log.txt").string() + "'";
  const int raw = std::system(cmd.c_str());
  p.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  p.dom = readFile(work / "dom.html");
  p.log = readFile(work / "log.txt");
  p.console = consoleMessages(p.log);
  return p;
}

struct ScreenshotVerdict {
  bool blank = true;
  double inked = 0;          // fraction of pixels that are not (near) white
  std::size_t distinct = 0;  // distinct 8-bit RGB values
};

// A page that rendered text, tables and charts has many colours and a few
// percent of non-white pixels; a blank (or failed) page has one colour.
inline ScreenshotVerdict inspectScreenshot(const std::filesystem::path& png) {
  ScreenshotVerdict v;
  if (!std::filesystem::exists(png)) return v;
  const sb::Image img = sb::readImage(png.string());
  std::set<std::uint32_t> colors;
  std::size_t inked = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      std::uint32_t code = 0;
      bool white = true;
      for (int c = 0; c < 3; ++c) {
        const float s = img.at(x, y, c);
        white &= s > 0.95f;
        code = code << 8 | static_cast<std::uint32_t>(s * 255.0f + 0.5f);
      }
      colors.insert(code);
      inked += white ? 0 : 1;
    }
  }
  v.distinct = colors.size();
  v.inked = img.empty() ? 0.0 : static_cast<double>(inked) / (double(img.width) * img.height);
  v.blank = v.distinct < 16 || v.inked < 0.01;
  return v;
}

}  // namespace sbtest
