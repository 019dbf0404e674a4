// The baseline manifest (baselines/manifest.json) read and checked: every key, setting
// and tolerance named where it is wrong (harness/baselines.h).
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

#include "harness/baselines.h"
#include "harness/checks.h"
#include "harness/json_keys.h"
#include "harness/settings.h"
#include "harness/stop.h"
#include "harness/unit_cases.h"
#include "reports/json_file.h"
#include "scenes/scene.h"

namespace sb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// "unit_cases": true adds the cases the unit folders carry (harness/unit_cases.h).
const std::vector<std::string> kTopKeys = {"comment",  "format", "tolerances",
                                           "defaults", "cases",  "unit_cases"};
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
  if (format != 1) keys.push_back("driver_tolerances");
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
  // A driver's tolerance (by driverKey): fields over the case's tolerance.
  std::map<std::string, PartialTolerance> driverTolerances;

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
    std::map<std::string, std::string> seen;
    addCases(root["cases"], "cases", defaults, seen, m);
    if (root.contains("unit_cases") && !root["unit_cases"].is_boolean())
      fail("unit_cases", "must be true or false");
    if (root.value("unit_cases", false))
      for (const UnitCaseFile& u : unitCaseFiles(file_)) {
        const json doc = parseJson<json>(u.text, u.file.string());
        sb::checkKeys(doc, unitCaseKeys(), u.file.string(), "key");
        if (doc.contains("baselines"))
          addCases(doc["baselines"], u.file.string() + ": baselines", defaults, seen, m);
      }
    return m;
  }

 private:
  // The cases of one array (`where`: "cases", or a unit's file), their names unique over all.
  void addCases(const json& cases, const std::string& where, const PartialCase& defaults,
                std::map<std::string, std::string>& seen, Manifest& m) const {
    if (!cases.is_array()) fail(where, "must be an array of cases");
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const std::string index = where + "[" + std::to_string(i) + "]";
      std::string at = index;
      const json& c = cases[i];
      if (!c.is_object()) fail(at, "must be an object");
      if (c.contains("name") && c["name"].is_string())
        at += " ('" + c["name"].get<std::string>() + "')";
      PartialCase p = defaults;
      apply(c, at, p);
      BaselineCase bc = finish(p, at);
      if (auto it = seen.find(bc.name); it != seen.end())
        fail(at, "duplicate case name '" + bc.name + "' (also " + it->second + ")");
      seen[bc.name] = index;
      m.cases.push_back(std::move(bc));
    }
  }

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
    if (obj.contains("driver_tolerances")) {
      const json& d = obj["driver_tolerances"];
      if (!d.is_object())
        fail(where, "\"driver_tolerances\" must be an object: driver name -> tolerance");
      for (const auto& [driver, t] : d.items()) {
        const std::string at = where + ".driver_tolerances." + driver;
        if (t.is_string()) {
          auto it = presets_.find(t.get<std::string>());
          if (it == presets_.end()) fail(at, "unknown tolerance '" + t.get<std::string>() + "'");
          p.driverTolerances[driver] = it->second;
        } else if (t.is_object()) {
          p.driverTolerances[driver] = tolerance(t, at);
        } else {
          fail(at, "must be the name of one in \"tolerances\" or an object");
        }
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
    auto whole = [](const PartialTolerance& t) {
      return Tolerance{*t.maxAbs, *t.maxFailingFraction, *t.failingThreshold, *t.minPsnr,
                       t.maxFlipMean.value_or(kInf)};
    };
    c.tolerance = whole(p.tolerance);
    for (const auto& [driver, t] : p.driverTolerances) {
      PartialTolerance own = p.tolerance;
      own.overlay(t);
      c.driverTolerances[driver] = whole(own);
    }
    return c;
  }

  fs::path file_;
  int format_ = kFormat;
  std::map<std::string, PartialTolerance> presets_;
};

}  // namespace

Manifest loadManifest(const fs::path& file) { return ManifestReader(file).read(); }

}  // namespace sb
