#include "harness/baselines.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>

#include "backends/driver_env.h"
#include "harness/checks.h"
#include "harness/expectations.h"
#include "harness/json_keys.h"
#include "harness/measures/invariants/invariants.h"
#include "harness/settings.h"
#include "harness/stop.h"
#include "reports/json_file.h"
#include "scenes/scene.h"

namespace sb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// ------------------------------------------------------------------ helpers

std::string fmt(double v, int digits = 3) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string sizeText(const Image& img) {
  return std::to_string(img.width) + "x" + std::to_string(img.height);
}

json toleranceJson(const Tolerance& t) {
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return json{{"max_abs", num(t.maxAbs)},
              {"max_failing_fraction", t.maxFailingFraction},
              {"failing_threshold", t.failingThreshold},
              {"min_psnr", num(t.minPsnr)},
              {"max_flip_mean", num(t.maxFlipMean)}};
}

// Runs f; bad scene or technique specs name the manifest and the case.
template <typename F>
auto forCase(const Manifest& m, const BaselineCase& c, const std::string& backend, F&& f)
    -> decltype(f()) {
  const std::string where = m.file.string() + ": case '" + c.name + "' (" + backend + "): ";
  try {
    return f();
  } catch (const UnavailableError& e) {  // a part this driver lacks: check and bless skip it
    throw UnavailableError(where + e.what(), e.enable);
  } catch (const InputError& e) {
    throw InputError(where + e.what());
  }
}

// Renders a case (its scene from the cache that checkCases filled).
RenderResult renderCase(const Manifest& m, const BaselineCase& c, const std::string& backend,
                        RenderCache& cache) {
  throwIfStopped();  // between cases; runRender checks between passes
  return forCase(m, c, backend, [&] { return runRender(caseRequest(c, backend), &cache); });
}

// Everything the cases name (scenes, techniques, sizes, each backend's device),
// checked before the first render: a bad case or an unavailable backend stops
// check or bless before it prints or writes anything. Keeps the scenes in `cache`.
void checkCases(const Manifest& m, const std::vector<BaselineCase>& cases, RenderCache& cache) {
  std::set<std::string> devices;
  for (const BaselineCase& c : cases)
    for (const std::string& backend : c.backends) {
      const bool device = devices.insert(backend).second;
      forCase(m, c, backend,
              [&] { checkRenderRequest(caseRequest(c, backend), device, &cache, Spelling::Json); });
    }
}

// The folder given by --baselines must exist (it holds manifest.json).
void checkBaselinesFolder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec))
    throw InputError("--baselines " + dir.string() + ": no such baselines folder");
  if (!fs::is_directory(dir, ec))
    throw InputError("--baselines " + dir.string() + ": is a file, not a baselines folder");
}

// A folder path without a trailing separator, absolute.
fs::path folderPath(const fs::path& p) {
  fs::path a = fs::absolute(p).lexically_normal();
  if (a.filename().empty() && a.has_parent_path()) a = a.parent_path();
  return a;
}

// Converts filesystem errors into InputError (exit 2) naming the paths.
template <typename F>
auto fsGuard(F&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const fs::filesystem_error& e) {
    throw InputError(e.what());
  }
}

struct Counts {
  int passed = 0, failed = 0, missing = 0;
  int expectedFailures = 0, flakes = 0, skipped = 0, unexpectedPasses = 0;
};

// One comparison of a case: a backend's image against its baseline, or a further backend's
// against the first's ("gl-vs-vulkan").
struct Outcome {
  std::string label;
  Verdict verdict;         // failures empty: passed
  bool missing = false;    // no baseline file
  bool comparison = true;  // false: a failure that is not a comparison (invariant, unreadable)
  Image actual;
  std::optional<Image> expected;
  std::string expectedName, actualName;
  fs::path baselineFile;
  bool ok() const { return !missing && verdict.ok(); }
};

// What the expectations and the re-runs make of an outcome.
enum class Class { Passed, Failed, Missing, ExpectedFailure, KnownFlake, NewFlake, UnexpectedPass };

// An expectation's reason on the console: its first clause (the whole is in the file and
// in the comparison's JSON).
std::string brief(const std::string& reason) {
  std::string s = reason.substr(0, reason.find(": "));
  if (s.size() > 100) s = s.substr(0, 97) + "...";
  return s;
}

std::string reasonsText(const Verdict& v) {
  std::string reasons;
  for (const auto& f : v.failures) reasons += (reasons.empty() ? "" : "; ") + f;
  return reasons;
}

class Checker {
 public:
  // `baselines`: the folder checked, which the hint to bless a missing case names.
  Checker(fs::path outDir, fs::path baselines, std::ostream& out)
      : outDir_(std::move(outDir)), baselines_(std::move(baselines)), out_(out) {}

  // Prints one line for the outcome as classified; writes the files of anything that
  // did not pass (the actual image, the expected one, the heatmap, the numbers).
  void report(const BaselineCase& c, const Outcome& o, Class k, const std::string& note) {
    clearStale(c.name, o.label);
    const ImageError& e = o.verdict.error;
    const std::string stem = (outDir_ / (c.name + "." + o.label)).string();
    const std::string suffix = note.empty() ? "" : " (" + note + ")";
    switch (k) {
      case Class::Passed:
      case Class::UnexpectedPass:
        if (k == Class::Passed) {
          ++counts.passed;
          out_ << "OK ";
        } else {
          ++counts.unexpectedPasses;
          out_ << "UNEXPECTED PASS ";
        }
        out_ << c.name << " " << o.label << ": max_abs " << fmt(e.maxAbs) << ", failing "
             << fmt(e.fractionOver) << ", psnr " << fmt(e.psnr) << " dB, ssim " << fmt(e.ssim, 6);
        if (o.verdict.flip) out_ << ", flip " << fmt(o.verdict.flip->mean);
        out_ << suffix << "\n";
        return;
      case Class::Missing:
        missing(c, o);
        return;
      case Class::Failed:
        ++counts.failed;
        out_ << "FAILED ";
        break;
      case Class::ExpectedFailure:
        ++counts.expectedFailures;
        out_ << "EXPECTED FAIL ";
        break;
      case Class::KnownFlake:
      case Class::NewFlake:
        ++counts.flakes;
        out_ << "FLAKE ";
        break;
    }
    out_ << c.name << " " << o.label << ": " << reasonsText(o.verdict);
    if (e.width > 0 && o.comparison) out_ << " (ssim " << fmt(e.ssim, 6) << ")";
    out_ << suffix << " -> " << stem << ".*\n";
    writeFailure(c, o, k);
  }

  Counts counts;

 private:
  void missing(const BaselineCase& c, const Outcome& o) {
    ++counts.missing;
    const std::string stem = (outDir_ / (c.name + "." + o.label)).string();
    // The hint, followed as printed, blesses this case in this folder (a bare
    // `strandbench bless` would re-render every case of the repository's baselines).
    std::string pattern;  // the name, matched whole, its regex characters escaped
    for (char ch : c.name) {
      if (std::string_view(".^$|()[]{}*+?\\").find(ch) != std::string_view::npos) pattern += '\\';
      pattern += ch;
    }
    out_ << "MISSING " << c.name << " " << o.label << ": no baseline " << o.baselineFile.string()
         << " (actual -> " << stem << ".actual.png; run `strandbench bless --baselines "
         << shellQuoted(baselines_.string()) << " --filter " << shellQuoted("^" + pattern + "$")
         << "`)\n";
    writeFailure(c, o, Class::Missing);
  }

  void clearStale(const std::string& name, const std::string& label) {
    for (const char* suffix : {".actual.png", ".expected.png", ".diff.png", ".json"}) {
      std::error_code ec;
      fs::remove(outDir_ / (name + "." + label + suffix), ec);
    }
  }

  void writeFailure(const BaselineCase& c, const Outcome& o, Class k) {
    static const char* const kNames[] = {"passed",           "failed",      "missing",
                                         "expected failure", "known flake", "flake",
                                         "unexpected pass"};
    fs::create_directories(outDir_);
    const std::string stem = (outDir_ / (c.name + "." + o.label)).string();
    writeImage(o.actual, stem + ".actual.png", ImageBitDepth::U16);
    const RenderRequest& r = c.request;
    std::vector<std::string> failures = o.verdict.failures;
    if (o.missing) failures = {"missing baseline " + o.baselineFile.string()};
    json j{{"case", c.name},
           {"label", o.label},
           {"outcome", kNames[static_cast<int>(k)]},
           {"scene", r.scene},
           {"shadow", r.shadow},
           {"oit", r.oit},
           {"size", std::to_string(r.width) + "x" + std::to_string(r.height)},
           {"primitive", r.primitive},
           {"expected", o.expectedName},
           {"actual", o.actualName},
           {"tolerance", toleranceJson(c.tolerance)},
           {"failures", failures},
           {"files", {{"actual", stem + ".actual.png"}}}};
    if (o.expected) {
      const Image& expected = *o.expected;
      writeImage(expected, stem + ".expected.png", ImageBitDepth::U16);
      j["files"]["expected"] = stem + ".expected.png";
      if (expected.width == o.actual.width && expected.height == o.actual.height) {
        const double m = o.verdict.error.maxAbs;
        const double scale = std::isfinite(m) && m > 0.0 ? m : 1.0;
        writeImage(diffHeatmap(o.actual, expected, scale), stem + ".diff.png");
        j["files"]["diff"] = stem + ".diff.png";
        j["heatmap_scale"] = scale;
        j["metrics"] = toJson(o.verdict.error);
        j["metrics"]["failing_threshold"] = c.tolerance.failingThreshold;
        if (o.verdict.flip) j["metrics"]["flip"] = toJson(*o.verdict.flip);
      }
    }
    std::ofstream f(stem + ".json");
    f << j.dump(2) << "\n";
    if (!f) throw InputError(stem + ".json: cannot write");
  }

  fs::path outDir_, baselines_;
  std::ostream& out_;
};

// The most specific baseline image of a case on a backend: "<case>.<backend>.<driver>.png"
// where the driver has its own, else the backend's "<case>.<backend>.png".
fs::path baselineFile(const fs::path& dir, const std::string& caseName, const std::string& backend,
                      const std::string& driver) {
  const fs::path own = dir / (caseName + "." + backend + "." + driverKey(driver) + ".png");
  if (fs::exists(own)) return own;
  return dir / baselineFileName(caseName, backend);
}

// The tolerance of a case on a driver: the driver's own where the manifest gives one.
const Tolerance& caseTolerance(const BaselineCase& c, const std::string& driver) {
  const auto it = c.driverTolerances.find(driverKey(driver));
  return it == c.driverTolerances.end() ? c.tolerance : it->second;
}

// SB_CHECK_TEST_DIFFER=CASE:N, a test hook: the first N renders of CASE in this check get
// a bright 4x4 block, so that a test can make a case differ on its first run only (a flake)
// or on every run (a failure).
struct DifferHook {
  std::string caseName;
  long renders = 0;
  long seen = 0;
  DifferHook() {
    const char* v = std::getenv("SB_CHECK_TEST_DIFFER");
    if (!v || !*v) return;
    const std::string s = v;
    const auto colon = s.rfind(':');
    char* end = nullptr;
    if (colon != std::string::npos) renders = std::strtol(s.c_str() + colon + 1, &end, 10);
    if (colon == std::string::npos || colon == 0 || !end || *end != '\0' || renders < 0)
      throw InputError("SB_CHECK_TEST_DIFFER=" + s + ": expected CASE:N");
    caseName = s.substr(0, colon);
  }
  void apply(const std::string& name, Image& img) {
    if (name != caseName || seen++ >= renders) return;
    for (int y = 0; y < std::min(4, img.height); ++y)
      for (int x = 0; x < std::min(4, img.width); ++x)
        for (int ch = 0; ch < 3; ++ch) img.pixels[img.index(x, y, ch)] = 1.0f;
  }
};

long abortAfterFromEnv() {
  const char* v = std::getenv("SB_BLESS_ABORT_AFTER");
  if (!v || !*v) return -1;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  if (*end != '\0' || n < 0)
    throw InputError(std::string("SB_BLESS_ABORT_AFTER=") + v + ": expected a count >= 0");
  return n;
}

// Removes the staging folder unless released (the swap happened).
struct StagingGuard {
  fs::path path;
  bool active = true;
  ~StagingGuard() {
    if (active) {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  }
};

}  // namespace

// ------------------------------------------------------------------ public

std::vector<BaselineCase> selectCases(const Manifest& m, const std::string& regex) {
  if (regex.empty()) return m.cases;
  std::regex re;
  try {
    re = std::regex(regex, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw InputError("--filter '" + regex + "': not a valid regular expression (" + e.what() + ")");
  }
  std::vector<BaselineCase> out;
  for (const auto& c : m.cases)
    if (std::regex_search(c.name, re)) out.push_back(c);
  if (out.empty())
    throw InputError("--filter '" + regex + "' matches no case in " + m.file.string());
  return out;
}

std::string baselineFileName(const std::string& caseName, const std::string& backend) {
  return caseName + "." + backend + ".png";
}

RenderRequest caseRequest(const BaselineCase& c, const std::string& backend) {
  RenderRequest r = c.request;
  r.backend = backend;
  return r;
}

Image quantize16(const Image& img) {
  Image q = img;
  for (float& v : q.pixels) {
    if (std::isnan(v)) continue;
    // Same arithmetic as writeImage (float product, lround) and readImage.
    const long code = std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f);
    v = static_cast<float>(code) * (1.0f / 65535.0f);
  }
  return q;
}

Verdict judge(const Image& actual, const Image& expected, const Tolerance& t) {
  Verdict v;
  v.error = compareImages(actual, expected, t.failingThreshold, 3);
  const ImageError& e = v.error;
  if (e.nanPixels > 0) v.failures.push_back(std::to_string(e.nanPixels) + " NaN pixels");
  if (!(e.maxAbs <= t.maxAbs))
    v.failures.push_back("max_abs " + fmt(e.maxAbs) + " > " + fmt(t.maxAbs));
  if (!(e.fractionOver <= t.maxFailingFraction))
    v.failures.push_back("failing " + fmt(e.fractionOver) + " (" + std::to_string(e.pixelsOver) +
                         " px over " + fmt(t.failingThreshold) + ") > " +
                         fmt(t.maxFailingFraction));
  if (!(e.psnr >= t.minPsnr))
    v.failures.push_back("psnr " + fmt(e.psnr) + " dB < " + fmt(t.minPsnr) + " dB");
  if (std::isfinite(t.maxFlipMean)) {
    v.flip = computeFlip(actual, expected);
    if (!(v.flip->mean <= t.maxFlipMean))
      v.failures.push_back("flip mean " + fmt(v.flip->mean) + " > " + fmt(t.maxFlipMean));
  }
  return v;
}

namespace {

// Renders a case on its backends (those not skipped) and makes its comparisons.
std::vector<Outcome> runComparisons(const Manifest& m, const BaselineCase& c, const fs::path& dir,
                                    const std::string& driver, const Expectations& x,
                                    RenderCache& cache, DifferHook& hook, int& renders) {
  const Tolerance& tolerance = caseTolerance(c, driver);
  std::vector<Outcome> outcomes;
  std::vector<std::pair<std::string, Image>> images;  // (backend, image)
  for (const std::string& backend : c.backends) {
    if (Expectations::find(x.skips, c.name, backend)) continue;
    const RenderResult result = renderCase(m, c, backend, cache);
    Image actual = result.image;
    hook.apply(c.name, actual);
    actual = quantize16(actual);
    ++renders;
    Outcome o;
    o.label = backend;
    o.actual = actual;
    o.actualName = "rendered on " + backend;
    if (const InvariantsResult* inv = result.measure<InvariantsResult>();
        inv && !inv->failures.empty()) {
      std::string what;
      for (const auto& f : inv->failures)
        what += (what.empty() ? "" : "; ") + f.pass + ": " + f.what;
      o.comparison = false;
      o.verdict.failures.push_back("invariant failed: " + what);
    } else {
      o.baselineFile = baselineFile(dir, c.name, backend, driver);
      o.expectedName = o.baselineFile.string();
      if (!fs::exists(o.baselineFile)) {
        o.missing = true;
      } else {
        try {
          o.expected = readImage(o.baselineFile.string());
        } catch (const InputError& e) {
          o.comparison = false;
          o.verdict.failures.push_back(std::string("unreadable baseline: ") + e.what());
        }
      }
      if (o.expected) {
        if (o.expected->width != actual.width || o.expected->height != actual.height)
          o.verdict.failures.push_back("size " + sizeText(actual) + " but " + o.expectedName +
                                       " is " + sizeText(*o.expected));
        else
          o.verdict = judge(actual, *o.expected, tolerance);
      }
    }
    outcomes.push_back(std::move(o));
    images.emplace_back(backend, actual);
  }
  // Each further backend against the first (GL against Vulkan), same tolerance.
  for (std::size_t i = 1; i < images.size(); ++i) {
    Outcome o;
    o.label = images[0].first + "-vs-" + images[i].first;
    if (images[0].first != c.backends[0] || Expectations::find(x.skips, c.name, o.label)) continue;
    o.actual = images[i].second;
    o.expected = images[0].second;
    o.expectedName = "rendered on " + images[0].first;
    o.actualName = "rendered on " + images[i].first;
    o.verdict = judge(o.actual, *o.expected, tolerance);
    outcomes.push_back(std::move(o));
  }
  return outcomes;
}

}  // namespace

int runCheck(const CheckOptions& opt, std::ostream& out) {
  return fsGuard([&] {
    const fs::path dir = folderPath(opt.baselines);
    checkBaselinesFolder(dir);
    const Manifest m = loadManifest(dir / "manifest.json");
    const std::vector<BaselineCase> cases = selectCases(m, opt.filter);
    if (opt.retries < 0) throw InputError("--retries: a count >= 0");
    const std::string driver = currentDriver();
    Expectations x;
    if (opt.expectations != "none") {
      const fs::path file =
          opt.expectations.empty() ? expectationsFile(dir, driver) : fs::path(opt.expectations);
      if (!opt.expectations.empty() || fs::exists(file)) {
        x = loadExpectations(file, m);
        if (x.driver != driverKey(driver))
          throw InputError(file.string() + ": describes driver '" + x.driver +
                           "' but this check runs '" + driverKey(driver) + "'");
      }
    }
    DifferHook hook;
    RenderCache cache;
    checkCases(m, cases, cache);
    const auto t0 = std::chrono::steady_clock::now();
    Checker checker(opt.outDir, dir, out);
    if (!x.file.empty())
      out << "driver " << driverKey(driver) << ", expectations " << x.file.string() << " ("
          << x.failures.size() << " failures, " << x.flakes.size() << " flakes, " << x.skips.size()
          << " skips)\n";
    int renders = 0;
    for (const BaselineCase& c : cases) {
      if (const Expectation* s = Expectations::find(x.skips, c.name, "");
          s && s->comparison.empty()) {
        ++checker.counts.skipped;
        out << "SKIP " << c.name << ": " << s->reason << "\n";
        continue;
      }
      for (const std::string& backend : c.backends)
        if (const Expectation* s = Expectations::find(x.skips, c.name, backend)) {
          ++checker.counts.skipped;
          out << "SKIP " << c.name << " " << backend << ": " << s->reason << "\n";
        }
      // A part this driver lacks (mesh shaders on Mesa 22.3.6): the case is skipped, as a
      // sweep leaves such a case out.
      std::vector<Outcome> first;
      try {
        first = runComparisons(m, c, dir, driver, x, cache, hook, renders);
      } catch (const UnavailableError& e) {
        ++checker.counts.skipped;
        out << "SKIP " << c.name << ": " << e.what() << " (" << e.enable << ")\n";
        continue;
      }
      // A failure nobody expected is re-run, the whole case on a fresh device each time: a
      // comparison that passes on a re-run is a flake, one that fails every time a failure.
      std::set<std::string> pending;
      for (const Outcome& o : first)
        if (!o.ok() && !o.missing && !Expectations::find(x.failures, c.name, o.label) &&
            !Expectations::find(x.flakes, c.name, o.label))
          pending.insert(o.label);
      std::map<std::string, int> passedOnRun;
      int runs = 1;
      for (int r = 0; r < opt.retries && !pending.empty(); ++r) {
        ++runs;
        for (const Outcome& o : runComparisons(m, c, dir, driver, x, cache, hook, renders))
          if (pending.count(o.label) && o.ok()) {
            passedOnRun[o.label] = runs;
            pending.erase(o.label);
          }
      }
      for (const Outcome& o : first) {
        const Expectation* fails = Expectations::find(x.failures, c.name, o.label);
        const Expectation* flaky = Expectations::find(x.flakes, c.name, o.label);
        if (o.missing) {
          checker.report(c, o, Class::Missing, "");
        } else if (o.ok()) {
          if (fails)
            checker.report(c, o, Class::UnexpectedPass,
                           "expected to fail: " + brief(fails->reason) + "; remove it from " +
                               x.file.string());
          else
            checker.report(c, o, Class::Passed,
                           flaky ? "known flake: " + brief(flaky->reason) : "");
        } else if (fails) {
          checker.report(c, o, Class::ExpectedFailure, "expected: " + brief(fails->reason));
        } else if (flaky) {
          checker.report(c, o, Class::KnownFlake, "known flake: " + brief(flaky->reason));
        } else if (passedOnRun.count(o.label)) {
          checker.report(c, o, Class::NewFlake,
                         "failed on run 1, passed on run " + std::to_string(passedOnRun[o.label]) +
                             "; list it under \"flakes\" in " +
                             expectationsFile(dir, driver).string() + " if it recurs");
        } else {
          checker.report(c, o, Class::Failed,
                         runs > 1 ? "failed on all " + std::to_string(runs) + " runs" : "");
        }
      }
      out.flush();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Counts& n = checker.counts;
    out << "check: " << cases.size() << " cases, " << renders << " renders in " << fmt(seconds)
        << " s\n";
    out << n.passed << " passed, " << n.failed << " failed, " << n.missing << " missing";
    for (const auto& [count, what] :
         {std::pair{n.expectedFailures, "expected failures"}, std::pair{n.flakes, "flakes"},
          std::pair{n.skipped, "skipped"}, std::pair{n.unexpectedPasses, "unexpected passes"}})
      if (count > 0 || !x.file.empty()) out << ", " << count << " " << what;
    out << "\n";
    return n.failed + n.missing + n.unexpectedPasses > 0 ? 1 : 0;
  });
}

fs::path swapDirectories(const fs::path& replacement, const fs::path& current,
                         const fs::path& aside) {
  if (::renameat2(AT_FDCWD, replacement.c_str(), AT_FDCWD, current.c_str(), RENAME_EXCHANGE) == 0)
    return replacement;
  const int err = errno;
  if (err != EINVAL && err != ENOSYS && err != ENOTSUP && err != EOPNOTSUPP)
    throw InputError("cannot swap " + replacement.string() + " into " + current.string() + ": " +
                     std::strerror(err));
  // The filesystem refuses RENAME_EXCHANGE: two renames (a short window where
  // `current` is absent; the next bless restores `aside` if it stopped there).
  if (::rename(current.c_str(), aside.c_str()) != 0)
    throw InputError("cannot move " + current.string() + " to " + aside.string() + ": " +
                     std::strerror(errno));
  if (::rename(replacement.c_str(), current.c_str()) != 0) {
    const int e2 = errno;
    ::rename(aside.c_str(), current.c_str());
    throw InputError("cannot move " + replacement.string() + " to " + current.string() + ": " +
                     std::strerror(e2));
  }
  return aside;
}

int runBless(const fs::path& baselines, const std::string& filter, std::ostream& out) {
  return fsGuard([&] {
    const long abortAfter = abortAfterFromEnv();
    const fs::path dir = folderPath(baselines);
    const fs::path parent = dir.parent_path();
    const std::string prefix = "." + dir.filename().string() + ".bless-";
    // A bless stopped between the two fallback renames leaves no `dir` but an
    // "old" copy: put it back.
    if (!fs::exists(dir) && fs::is_directory(parent)) {
      for (const auto& entry : fs::directory_iterator(parent)) {
        const std::string n = entry.path().filename().string();
        if (n.rfind(prefix + "old-", 0) == 0 && entry.is_directory()) {
          fs::rename(entry.path(), dir);
          out << "restored " << dir.string() << " from " << entry.path().string() << "\n";
          break;
        }
      }
    }
    checkBaselinesFolder(dir);
    const Manifest m = loadManifest(dir / "manifest.json");
    const std::vector<BaselineCase> cases = selectCases(m, filter);
    RenderCache cache;
    checkCases(m, cases, cache);

    // Leftovers of a bless that was killed.
    std::vector<fs::path> leftovers;
    for (const auto& entry : fs::directory_iterator(parent))
      if (entry.path().filename().string().rfind(prefix, 0) == 0) leftovers.push_back(entry.path());
    for (const fs::path& p : leftovers) {
      fs::remove_all(p);
      out << "removed leftover " << p.string() << "\n";
    }

    const std::string pid = std::to_string(::getpid());
    StagingGuard staging{parent / (prefix + "staging-" + pid)};
    fs::copy(dir, staging.path, fs::copy_options::recursive);
    long written = 0;
    if (abortAfter == 0) std::_Exit(3);
    for (const BaselineCase& c : cases) {
      std::vector<Image> images;
      for (const std::string& backend : c.backends) {
        RenderResult r;
        try {
          r = renderCase(m, c, backend, cache);
        } catch (const UnavailableError& e) {  // blessed where the part is (kept here)
          out << "SKIP " << c.name << " " << backend << ": " << e.what() << " (" << e.enable
              << "); its baseline is kept\n";
          continue;
        }
        const std::string name = baselineFileName(c.name, backend);
        writeImage(r.image, (staging.path / name).string(), ImageBitDepth::U16);
        ++written;
        out << "wrote " << name << "\n";
        if (abortAfter >= 0 && written >= abortAfter) {
          out << "SB_BLESS_ABORT_AFTER=" << abortAfter << ": stopping now (simulated kill)\n";
          out.flush();
          std::_Exit(3);
        }
        images.push_back(quantize16(r.image));
      }
      for (std::size_t i = 1; i < images.size(); ++i) {
        const Verdict v = judge(images[i], images[0], c.tolerance);
        if (!v.ok()) {
          std::string reasons;
          for (const auto& f : v.failures) reasons += (reasons.empty() ? "" : "; ") + f;
          out << "WARNING " << c.name << " " << c.backends[0] << "-vs-" << c.backends[i]
              << ": backends disagree beyond the tolerance (" << reasons
              << "); `check` will fail this comparison\n";
        }
      }
    }
    throwIfStopped();  // the last moment a stop leaves the baselines as they were
    const fs::path old = swapDirectories(staging.path, dir, parent / (prefix + "old-" + pid));
    staging.active = false;
    fs::remove_all(old);
    out << "blessed " << written << " images (" << cases.size() << " cases) into " << dir.string()
        << "\n";
    return 0;
  });
}

fs::path defaultBaselinesDir() { return fs::path(SB_SOURCE_DIR) / "baselines"; }

}  // namespace sb
