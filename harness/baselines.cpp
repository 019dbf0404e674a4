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

#include "harness/checks.h"
#include "harness/json_keys.h"
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
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(m.file.string() + ": case '" + c.name + "' (" + backend + "): " + e.what());
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
};

class Checker {
 public:
  // `baselines`: the folder checked, which the hint to bless a missing case names.
  Checker(fs::path outDir, fs::path baselines, std::ostream& out)
      : outDir_(std::move(outDir)), baselines_(std::move(baselines)), out_(out) {}

  // Compares actual with expected and prints one line; writes the failure files.
  void compare(const BaselineCase& c, const std::string& label, const Image& actual,
               const Image& expected, const std::string& expectedName,
               const std::string& actualName) {
    clearStale(c.name, label);
    Verdict v;
    if (actual.width != expected.width || actual.height != expected.height) {
      v.failures.push_back("size " + sizeText(actual) + " but " + expectedName + " is " +
                           sizeText(expected));
    } else {
      v = judge(actual, expected, c.tolerance);
    }
    const ImageError& e = v.error;
    if (v.ok()) {
      ++counts.passed;
      out_ << "OK " << c.name << " " << label << ": max_abs " << fmt(e.maxAbs) << ", failing "
           << fmt(e.fractionOver) << ", psnr " << fmt(e.psnr) << " dB, ssim " << fmt(e.ssim, 6);
      if (v.flip) out_ << ", flip " << fmt(v.flip->mean);
      out_ << "\n";
      return;
    }
    ++counts.failed;
    std::string reasons;
    for (const auto& f : v.failures) reasons += (reasons.empty() ? "" : "; ") + f;
    const std::string stem = (outDir_ / (c.name + "." + label)).string();
    out_ << "FAILED " << c.name << " " << label << ": " << reasons;
    if (e.width > 0) out_ << " (ssim " << fmt(e.ssim, 6) << ")";
    out_ << " -> " << stem << ".*\n";
    writeFailure(c, label, actual, &expected, v, expectedName, actualName);
  }

  void missing(const BaselineCase& c, const std::string& backend, const Image& actual,
               const fs::path& file) {
    clearStale(c.name, backend);
    ++counts.missing;
    const std::string stem = (outDir_ / (c.name + "." + backend)).string();
    // The hint, followed as printed, blesses this case in this folder (a bare
    // `strandbench bless` would re-render every case of the repository's baselines).
    std::string pattern;  // the name, matched whole, its regex characters escaped
    for (char ch : c.name) {
      if (std::string_view(".^$|()[]{}*+?\\").find(ch) != std::string_view::npos) pattern += '\\';
      pattern += ch;
    }
    out_ << "MISSING " << c.name << " " << backend << ": no baseline " << file.string()
         << " (actual -> " << stem << ".actual.png; run `strandbench bless --baselines "
         << shellQuoted(baselines_.string()) << " --filter " << shellQuoted("^" + pattern + "$")
         << "`)\n";
    Verdict v;
    v.failures.push_back("missing baseline " + file.string());
    writeFailure(c, backend, actual, nullptr, v, file.string(), "rendered on " + backend);
  }

  // A failure that is not a comparison: an unreadable baseline, a broken invariant.
  void failed(const BaselineCase& c, const std::string& backend, const Image& actual,
              const std::string& message) {
    clearStale(c.name, backend);
    ++counts.failed;
    const std::string stem = (outDir_ / (c.name + "." + backend)).string();
    out_ << "FAILED " << c.name << " " << backend << ": " << message << " -> " << stem << ".*\n";
    Verdict v;
    v.failures.push_back(message);
    writeFailure(c, backend, actual, nullptr, v, "", "rendered on " + backend);
  }

  Counts counts;

 private:
  void clearStale(const std::string& name, const std::string& label) {
    for (const char* suffix : {".actual.png", ".expected.png", ".diff.png", ".json"}) {
      std::error_code ec;
      fs::remove(outDir_ / (name + "." + label + suffix), ec);
    }
  }

  void writeFailure(const BaselineCase& c, const std::string& label, const Image& actual,
                    const Image* expected, const Verdict& v, const std::string& expectedName,
                    const std::string& actualName) {
    fs::create_directories(outDir_);
    const std::string stem = (outDir_ / (c.name + "." + label)).string();
    writeImage(actual, stem + ".actual.png", ImageBitDepth::U16);
    const RenderRequest& r = c.request;
    json j{{"case", c.name},
           {"label", label},
           {"scene", r.scene},
           {"shadow", r.shadow},
           {"oit", r.oit},
           {"size", std::to_string(r.width) + "x" + std::to_string(r.height)},
           {"primitive", r.primitive},
           {"expected", expectedName},
           {"actual", actualName},
           {"tolerance", toleranceJson(c.tolerance)},
           {"failures", v.failures},
           {"files", {{"actual", stem + ".actual.png"}}}};
    if (expected) {
      writeImage(*expected, stem + ".expected.png", ImageBitDepth::U16);
      j["files"]["expected"] = stem + ".expected.png";
      if (expected->width == actual.width && expected->height == actual.height) {
        const double m = v.error.maxAbs;
        const double scale = std::isfinite(m) && m > 0.0 ? m : 1.0;
        writeImage(diffHeatmap(actual, *expected, scale), stem + ".diff.png");
        j["files"]["diff"] = stem + ".diff.png";
        j["heatmap_scale"] = scale;
        j["metrics"] = toJson(v.error);
        j["metrics"]["failing_threshold"] = c.tolerance.failingThreshold;
        if (v.flip) j["metrics"]["flip"] = toJson(*v.flip);
      }
    }
    std::ofstream f(stem + ".json");
    f << j.dump(2) << "\n";
    if (!f) throw InputError(stem + ".json: cannot write");
  }

  fs::path outDir_, baselines_;
  std::ostream& out_;
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

int runCheck(const fs::path& baselines, const fs::path& outDir, const std::string& filter,
             std::ostream& out) {
  return fsGuard([&] {
    const fs::path dir = folderPath(baselines);
    checkBaselinesFolder(dir);
    const Manifest m = loadManifest(dir / "manifest.json");
    const std::vector<BaselineCase> cases = selectCases(m, filter);
    RenderCache cache;
    checkCases(m, cases, cache);
    const auto t0 = std::chrono::steady_clock::now();
    Checker checker(outDir, dir, out);
    int renders = 0;
    for (const BaselineCase& c : cases) {
      std::vector<Image> images;
      for (const std::string& backend : c.backends) {
        const RenderResult result = renderCase(m, c, backend, cache);
        const Image actual = quantize16(result.image);
        ++renders;
        if (result.invariants && !result.invariants->empty()) {
          std::string what;
          for (const auto& f : *result.invariants)
            what += (what.empty() ? "" : "; ") + f.pass + ": " + f.what;
          checker.failed(c, backend, actual, "invariant failed: " + what);
          images.push_back(actual);
          continue;
        }
        const fs::path file = dir / baselineFileName(c.name, backend);
        if (!fs::exists(file)) {
          checker.missing(c, backend, actual, file);
        } else {
          std::optional<Image> expected;
          try {
            expected = readImage(file.string());
          } catch (const InputError& e) {
            checker.failed(c, backend, actual, std::string("unreadable baseline: ") + e.what());
          }
          if (expected)
            checker.compare(c, backend, actual, *expected, file.string(), "rendered on " + backend);
        }
        images.push_back(actual);
      }
      // Each further backend against the first (GL against Vulkan), same tolerance.
      for (std::size_t i = 1; i < images.size(); ++i) {
        const std::string label = c.backends[0] + "-vs-" + c.backends[i];
        checker.compare(c, label, images[i], images[0], "rendered on " + c.backends[0],
                        "rendered on " + c.backends[i]);
      }
      out.flush();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Counts& n = checker.counts;
    out << "check: " << cases.size() << " cases, " << renders << " renders in " << fmt(seconds)
        << " s\n";
    out << n.passed << " passed, " << n.failed << " failed, " << n.missing << " missing\n";
    return n.failed + n.missing > 0 ? 1 : 0;
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
        const RenderResult r = renderCase(m, c, backend, cache);
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
