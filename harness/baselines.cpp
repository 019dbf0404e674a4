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

#include "harness/commands.h"
#include "harness/json_keys.h"
#include "harness/settings.h"
#include "harness/stop.h"
#include "reports/json_file.h"
#include "scenes/scene.h"

namespace sb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------ manifest

const std::vector<std::string> kTopKeys = {"comment", "format", "tolerances", "defaults", "cases"};
// Format 1 (still read): these settings only, "size" a "WxH" string.
const std::vector<std::string> kFormat1Settings = {"scene",     "shadow",       "oit",     "size",
                                                   "primitive", "ribbon_width", "backends"};
// Format 2: every setting of the table (harness/settings.h) and "backends".
constexpr int kFormat = 2;

// The keys of a case in a manifest of `format`.
std::vector<std::string> caseKeys(int format) {
  std::vector<std::string> keys = {"comment", "name"};
  if (format == 1) {
    keys.insert(keys.end(), kFormat1Settings.begin(), kFormat1Settings.end());
  } else {
    for (const std::string& k : settingKeys()) keys.push_back(k);
    keys.push_back("backends");
  }
  keys.push_back("tolerance");
  return keys;
}
const std::vector<std::string> kToleranceKeys = {
    "comment", "max_abs", "max_failing_fraction", "failing_threshold", "min_psnr", "max_flip_mean"};

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

struct PartialTolerance {
  std::optional<double> maxAbs, maxFailingFraction, failingThreshold, minPsnr;
  std::optional<double> maxFlipMean;  // optional: absent is no limit
  void overlay(const PartialTolerance& o) {
    if (o.maxAbs) maxAbs = o.maxAbs;
    if (o.maxFailingFraction) maxFailingFraction = o.maxFailingFraction;
    if (o.failingThreshold) failingThreshold = o.failingThreshold;
    if (o.minPsnr) minPsnr = o.minPsnr;
    if (o.maxFlipMean) maxFlipMean = o.maxFlipMean;
  }
};

struct PartialCase {
  std::optional<std::string> name;
  RenderRequest request = manifestBase();
  bool hasScene = false, hasSize = false;
  std::optional<std::vector<std::string>> backends;
  PartialTolerance tolerance;

  // A check renders one frame with no warm-up unless a case says otherwise.
  static RenderRequest manifestBase() {
    RenderRequest r;
    r.repeat = 1;
    r.warmup = 0;
    return r;
  }
};

class ManifestReader {
 public:
  explicit ManifestReader(fs::path file) : file_(std::move(file)) {}

  Manifest read() {
    const json root = parse();
    if (!root.is_object()) fail("", "the manifest must be a JSON object");
    checkKeys(root, kTopKeys, "");
    if (root.contains("comment")) text(root, "comment", "");
    if (!root.contains("format")) fail("", "missing \"format\": " + std::to_string(kFormat));
    if (!root["format"].is_number_integer() || root["format"].get<long long>() < 1 ||
        root["format"].get<long long>() > kFormat)
      fail("", "\"format\" must be 1 or 2 (the versions this strandbench reads), got " +
                   root["format"].dump());
    format_ = root["format"].get<int>();

    if (root.contains("tolerances")) {
      const json& t = root["tolerances"];
      if (!t.is_object()) fail("tolerances", "must be an object of named tolerances");
      for (const auto& [name, value] : t.items()) {
        const std::string where = "tolerances." + name;
        if (!value.is_object()) fail(where, "must be an object");
        PartialTolerance p = tolerance(value, where);
        complete(p, where);
        presets_[name] = p;
      }
    }

    PartialCase defaults;
    if (root.contains("defaults")) {
      const json& d = root["defaults"];
      if (!d.is_object()) fail("defaults", "must be an object");
      for (const char* k : {"name", "scene"})
        if (d.contains(k)) fail("defaults", std::string("\"") + k + "\" belongs in each case");
      apply(d, "defaults", defaults);
    }

    Manifest m;
    m.file = file_;
    if (!root.contains("cases")) fail("", "missing \"cases\": [...]");
    const json& cases = root["cases"];
    if (!cases.is_array()) fail("cases", "must be an array of cases");
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      std::string where = "cases[" + std::to_string(i) + "]";
      const json& c = cases[i];
      if (!c.is_object()) fail(where, "must be an object");
      if (c.contains("name") && c["name"].is_string())
        where += " ('" + c["name"].get<std::string>() + "')";
      PartialCase p = defaults;
      apply(c, where, p);
      BaselineCase bc = finish(p, where);
      if (auto it = seen.find(bc.name); it != seen.end())
        fail(where, "duplicate case name '" + bc.name + "' (also cases[" +
                        std::to_string(it->second) + "])");
      seen[bc.name] = i;
      m.cases.push_back(std::move(bc));
    }
    return m;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file_.string() + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  json parse() const {
    if (!std::ifstream(file_, std::ios::binary))
      fail("", std::string("cannot read the manifest: ") + std::strerror(errno));
    return readJsonFile(file_);
  }

  void checkKeys(const json& obj, const std::vector<std::string>& known,
                 const std::string& where) const {
    sb::checkKeys(obj, known, file_.string() + (where.empty() ? "" : ": " + where), "key");
  }

  std::string text(const json& obj, const char* key, const std::string& where) const {
    const json& v = obj[key];
    if (!v.is_string()) fail(where, std::string("\"") + key + "\" must be a string");
    return v.get<std::string>();
  }

  // A number, or null for "no limit" where allowed.
  double number(const json& obj, const char* key, const std::string& where, double lo, double hi,
                std::optional<double> nullMeans) const {
    const json& v = obj[key];
    if (v.is_null() && nullMeans) return *nullMeans;
    if (!v.is_number())
      fail(where, std::string("\"") + key + "\" must be a number" + (nullMeans ? " or null" : ""));
    const double d = v.get<double>();
    if (!(d >= lo && d <= hi)) {
      std::ostringstream s;
      s << "\"" << key << "\" = " << d << " is out of range [" << lo << ", " << hi << "]";
      fail(where, s.str());
    }
    return d;
  }

  PartialTolerance tolerance(const json& obj, const std::string& where) const {
    checkKeys(obj, kToleranceKeys, where);
    if (obj.contains("comment")) text(obj, "comment", where);
    PartialTolerance t;
    if (obj.contains("max_abs")) t.maxAbs = number(obj, "max_abs", where, 0.0, 1e9, kInf);
    if (obj.contains("max_failing_fraction"))
      t.maxFailingFraction = number(obj, "max_failing_fraction", where, 0.0, 1.0, std::nullopt);
    if (obj.contains("failing_threshold"))
      t.failingThreshold = number(obj, "failing_threshold", where, 0.0, 1e9, std::nullopt);
    if (obj.contains("min_psnr")) t.minPsnr = number(obj, "min_psnr", where, -1e9, 1e9, -kInf);
    if (obj.contains("max_flip_mean"))
      t.maxFlipMean = number(obj, "max_flip_mean", where, 0.0, 1.0, kInf);
    return t;
  }

  void complete(const PartialTolerance& t, const std::string& where) const {
    std::vector<std::string> lacking;
    if (!t.maxAbs) lacking.push_back("max_abs");
    if (!t.maxFailingFraction) lacking.push_back("max_failing_fraction");
    if (!t.failingThreshold) lacking.push_back("failing_threshold");
    if (!t.minPsnr) lacking.push_back("min_psnr");
    if (!lacking.empty()) fail(where, "tolerance lacks " + joined(lacking));
  }

  void apply(const json& obj, const std::string& where, PartialCase& p) const {
    const std::vector<std::string> keys = caseKeys(format_);
    if (format_ == 1 && obj.is_object())
      for (const auto& [key, value] : obj.items())
        if (std::find(keys.begin(), keys.end(), key) == keys.end() && findSetting(key))
          fail(where, "key '" + key + "' needs \"format\": 2 (format 1 cases take only " +
                          joined(kFormat1Settings) + ")");
    checkKeys(obj, keys, where);
    if (obj.contains("comment")) text(obj, "comment", where);
    if (obj.contains("name")) {
      p.name = text(obj, "name", where);
      static const std::regex kName("[A-Za-z0-9_-]+");
      if (!std::regex_match(*p.name, kName))
        fail(where, "name '" + *p.name +
                        "' must be letters, digits, '_' and '-' only (it names image files)");
    }
    if (obj.contains("backend") && obj.contains("backends"))
      fail(where, "give \"backend\" or \"backends\", not both");
    if (format_ == 1 && obj.contains("size") && !obj["size"].is_string())
      fail(where, "\"size\" " + obj["size"].dump() +
                      ": format 1 takes a \"WxH\" string (format 2 also a number N for NxN)");
    for (const Setting& setting : settingsTable()) {
      if (!obj.contains(setting.key)) continue;
      try {
        if (setting.key == "backend") {
          RenderRequest scratch;
          setFromJson(scratch, setting, obj[setting.key]);
          p.backends = std::vector<std::string>{scratch.backend};
        } else {
          setFromJson(p.request, setting, obj[setting.key]);
        }
      } catch (const InputError& e) {
        fail(where, e.what());
      }
    }
    p.hasScene = p.hasScene || obj.contains("scene");
    p.hasSize = p.hasSize || obj.contains("size");
    if (obj.contains("backends")) {
      try {
        p.backends = parseBackendList(obj["backends"]);
      } catch (const InputError& e) {
        fail(where, e.what());
      }
    }
    if (obj.contains("tolerance")) {
      const json& t = obj["tolerance"];
      if (t.is_string()) {
        auto it = presets_.find(t.get<std::string>());
        if (it == presets_.end()) {
          std::vector<std::string> names;
          for (const auto& [n, _] : presets_) names.push_back(n);
          fail(where, "unknown tolerance '" + t.get<std::string>() + "' (\"tolerances\" has: " +
                          (names.empty() ? "none" : joined(names)) + ")");
        }
        p.tolerance = it->second;
      } else if (t.is_object()) {
        p.tolerance.overlay(tolerance(t, where + ".tolerance"));
      } else {
        fail(where, "\"tolerance\" must be the name of one in \"tolerances\" or an object");
      }
    }
  }

  BaselineCase finish(const PartialCase& p, const std::string& where) const {
    BaselineCase c;
    if (!p.name) fail(where, "missing \"name\"");
    if (!p.hasScene) fail(where, "missing \"scene\"");
    if (!p.hasSize) fail(where, "missing \"size\" (in the case or in \"defaults\")");
    complete(p.tolerance, where);
    if (!p.request.image) fail(where, "\"image\": false: a baseline case compares its image");
    c.name = *p.name;
    c.request = p.request;
    if (p.backends) c.backends = *p.backends;
    // The rules between settings (a platform of each backend, a reference for invariants).
    for (const std::string& backend : c.backends) {
      try {
        checkRequest(caseRequest(c, backend), Spelling::Json);
      } catch (const InputError& e) {
        fail(where, e.what());
      }
    }
    c.tolerance = {*p.tolerance.maxAbs, *p.tolerance.maxFailingFraction,
                   *p.tolerance.failingThreshold, *p.tolerance.minPsnr,
                   p.tolerance.maxFlipMean.value_or(kInf)};
    return c;
  }

  fs::path file_;
  int format_ = kFormat;
  std::map<std::string, PartialTolerance> presets_;
};

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

Manifest loadManifest(const fs::path& file) { return ManifestReader(file).read(); }

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
