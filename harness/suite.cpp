#include "harness/suite.h"

#include <algorithm>
#include <cstdint>
#include <new>
#include <set>

#include "backends/driver_env.h"
#include "base/options.h"
#include "harness/json_keys.h"
#include "harness/settings.h"
#include "harness/technique_list.h"
#include "harness/unit_cases.h"
#include "render/common/technique.h"
#include "reports/files.h"
#include "reports/json_file.h"

namespace sb {

namespace {

using ojson = nlohmann::ordered_json;

// "figure" and "small": a figure's grid and its --small overrides (harness/figure.h); a sweep
// of a figure file runs its full size and ignores both.
// "unit_cases": true adds the groups the unit folders carry for the quick suite
// (harness/unit_cases.h).
const std::vector<std::string> kSuiteKeys = {"name",    "description", "defaults",
                                             "presets", "groups",      "tables",
                                             "figure",  "small",       "unit_cases"};
const std::vector<std::string> kGroupKeys = {"name", "description", "preset", "axes"};
// Settings: the table's keys (harness/settings.h), "backends", a list: one case per backend,
// and "drivers", a list: one case per driver (each driver's cases run in a process of its own).
std::vector<std::string> suiteSettings() {
  std::vector<std::string> keys = settingKeys();
  keys.push_back("backends");
  keys.push_back("drivers");
  return keys;
}
const std::vector<std::string> kSpecSettings = {"scene", "shadow", "oit"};

// An axis or setting value as text: strings as they are, numbers as JSON writes them.
std::string valueText(const ojson& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// Settings layered in order: later keys win ("backend" and "backends" replace each other).
void overlay(ojson& settings, const ojson& layer, const std::string& where) {
  const std::vector<std::string> keys = suiteSettings();
  for (const auto& [key, value] : layer.items()) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      throw InputError(where + ": " + unknownNameMessage("setting", key, keys));
    if (key == "backend") settings.erase("backends");
    if (key == "backends") settings.erase("backend");
    if (key == "driver") settings.erase("drivers");
    if (key == "drivers") settings.erase("driver");
    settings[key] = value;
  }
}

// Sets one option of a spec setting ("shadow.maps" = 16).
void setSpecOption(ojson& settings, const std::string& axis, const ojson& value,
                   const std::string& where) {
  const auto dot = axis.find('.');
  const std::string setting = axis.substr(0, dot), option = axis.substr(dot + 1);
  if (std::find(kSpecSettings.begin(), kSpecSettings.end(), setting) == kSpecSettings.end())
    throw InputError(where + ": axis '" + axis + "': only scene., shadow. and oit. options");
  if (option.empty()) throw InputError(where + ": axis '" + axis + "' names no option");
  const std::string base = settings.contains(setting)
                               ? valueText(settings[setting])
                               : settingText(RenderRequest{}, *findSetting(setting));
  Spec spec = Spec::parse(base);
  spec.options[option] = valueText(value);
  settings[setting] = spec.str();
}

RenderRequest toRequest(const ojson& s, const std::string& where) {
  RenderRequest r;
  try {
    // In table order, so that a case's first bad setting is the same whatever the layering.
    for (const Setting& setting : settingsTable())
      if (s.contains(setting.key)) setFromJson(r, setting, s.at(setting.key));
    // A suite may name any driver: a sweep runs each driver's cases in a process of its own
    // (harness/sweep.cpp); here the name only has to be a driver.
    const std::string driver = r.driver;
    r.driver.clear();
    checkRequest(r, Spelling::Json);
    if (!driver.empty()) {
      try {
        checkDriver(driver);
      } catch (const InputError& e) {
        // One scripts/drivers.sh fetches but this machine lacks: the sweep lists its cases as
        // not run (missingPart).
        if (!fetchableDriver(driver))
          throw InputError(
              settingMessage(*findSetting("driver"), Spelling::Json, driver, e.what()));
      }
      r.driver = driver;
    }
    // Technique specs are checked now, not half way through a sweep.
    checkTechniqueSpecs(r, Spelling::Json);
    const Spec scene = Spec::parse(r.scene);
    std::vector<std::string> scenes;
    for (const auto& info : sceneCatalog()) scenes.push_back(info.name);
    if (std::find(scenes.begin(), scenes.end(), scene.name) == scenes.end())
      throw InputError(settingMessage(*findSetting("scene"), Spelling::Json, r.scene,
                                      unknownNameMessage("scene", scene.name, scenes)));
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  return r;
}

// Every combination of the axes' values, the first axis outermost.
std::vector<ojson> combinations(const ojson& axes) {
  std::vector<ojson> out = {ojson::object()};
  for (const auto& [axis, values] : axes.items()) {
    std::vector<ojson> next;
    for (const auto& partial : out)
      for (const auto& v : values) {
        ojson c = partial;
        c[axis] = v;
        next.push_back(c);
      }
    out = std::move(next);
  }
  return out;
}

}  // namespace

bool fetchableDriver(const std::string& name) { return name == "mesa-25.0"; }

std::optional<UnavailableError> missingPart(const SweepCase& c) {
  const std::string& d = c.request.driver;
  if (d.empty()) return std::nullopt;
  try {
    checkDriver(d);
  } catch (const InputError& e) {
    return UnavailableError(e.what(), "scripts/drivers.sh (docs/drivers.md)");
  }
  return std::nullopt;
}

void checkSuiteFiles(const std::string& suiteFile, const std::vector<const SweepCase*>& cases) {
  std::set<std::string> seen;
  for (const SweepCase* c : cases) {
    const Spec spec = Spec::parse(c->request.scene);
    const bool namesFile = std::any_of(spec.options.begin(), spec.options.end(), [](const auto& o) {
      return (o.first == "path" || o.first == "mesh") && !o.second.empty();
    });
    if (!namesFile || !seen.insert(c->request.scene).second) continue;
    try {
      makeScene(spec);  // read whole and dropped: the case reads it again when it runs
    } catch (const InputError& e) {
      throw InputError(
          "suite " + suiteFile + ": case " + c->id + ": " +
          settingMessage(*findSetting("scene"), Spelling::Json, c->request.scene, e.what()));
    } catch (const DeviceError&) {  // out of memory: the case records it when it runs
    } catch (const std::bad_alloc&) {
    }
  }
}

std::string caseStem(const std::string& id) {
  std::string stem;
  for (char c : id)
    stem +=
        (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-') ? c : '_';
  uint32_t h = 2166136261u;  // FNV-1a: stable across runs and machines
  for (unsigned char c : id) h = (h ^ c) * 16777619u;
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", h);
  return stem + "-" + hex;
}

Suite parseSuite(const std::string& text, const std::string& file) {
  Suite suite;
  suite.file = file;
  suite.doc = parseJson<ojson>(text, file);
  const ojson& d = suite.doc;
  const std::string where = "suite " + file;
  checkKeys(d, kSuiteKeys, where, "suite key");
  if (d.contains("unit_cases") && !d["unit_cases"].is_boolean())
    throw InputError(where + ": \"unit_cases\" must be true or false");
  if (d.value("unit_cases", false) && d.contains("groups") && d["groups"].is_array())
    for (const UnitCaseFile& u : unitCaseFiles(file)) {
      const ojson unit = parseJson<ojson>(u.text, u.file.string());
      checkKeys(unit, unitCaseKeys(), u.file.string(), "key");
      if (!unit.contains("quick")) continue;
      if (!unit["quick"].is_array())
        throw InputError(u.file.string() + ": \"quick\" must be an array of groups");
      for (const ojson& g : unit["quick"]) suite.doc["groups"].push_back(g);
    }
  // The document now holds the units' groups: a run's stored copy of it (sweep.json), parsed
  // again, must not add them twice.
  suite.doc.erase("unit_cases");
  if (!d.contains("name") || !d["name"].is_string())
    throw InputError(where + ": \"name\" (a string) is required");
  suite.name = d["name"];
  suite.description = d.value("description", "");
  if (!d.contains("groups") || !d["groups"].is_array() || d["groups"].empty())
    throw InputError(where + ": \"groups\" must be a non-empty array");
  const ojson presets = d.value("presets", ojson::object());
  if (!presets.is_object()) throw InputError(where + ": \"presets\" must be an object");

  ojson base = {{"backends", backendNames()}};
  if (d.contains("defaults")) overlay(base, d["defaults"], where + ": defaults");

  std::set<std::string> groupNames, ids;
  for (const auto& g : d["groups"]) {
    if (!g.is_object() || !g.contains("name") || !g["name"].is_string())
      throw InputError(where + ": every group needs a \"name\" (a string)");
    const std::string name = g["name"];
    const std::string gwhere = where + ": group '" + name + "'";
    if (!groupNames.insert(name).second) throw InputError(gwhere + ": the name is used twice");
    if (name.find('/') != std::string::npos) throw InputError(gwhere + ": names cannot hold '/'");

    ojson settings = base;
    std::vector<std::string> presetNames;
    if (g.contains("preset")) {
      const ojson& p = g["preset"];
      if (p.is_string())
        presetNames.push_back(p);
      else if (p.is_array())
        for (const auto& x : p) presetNames.push_back(valueText(x));
      else
        throw InputError(gwhere + ": \"preset\" is a name or a list of names");
    }
    std::vector<std::string> known;
    for (const auto& [k, v] : presets.items()) known.push_back(k);
    for (const auto& pn : presetNames) {
      if (!presets.contains(pn))
        throw InputError(gwhere + ": " + unknownNameMessage("preset", pn, known));
      overlay(settings, presets[pn], gwhere + ": preset '" + pn + "'");
    }
    ojson own = ojson::object();
    for (const auto& [k, v] : g.items())
      if (std::find(kGroupKeys.begin(), kGroupKeys.end(), k) == kGroupKeys.end()) own[k] = v;
    overlay(settings, own, gwhere);

    ojson axes = g.value("axes", ojson::object());
    if (!axes.is_object()) throw InputError(gwhere + ": \"axes\" must be an object");
    const std::vector<std::string> axisNames = settingKeys();
    for (const auto& [axis, values] : axes.items()) {
      if (!values.is_array() || values.empty())
        throw InputError(gwhere + ": axis '" + axis + "' needs a non-empty array of values");
      if (axis.find('.') == std::string::npos &&
          std::find(axisNames.begin(), axisNames.end(), axis) == axisNames.end())
        throw InputError(gwhere + ": " + unknownNameMessage("axis", axis, axisNames));
    }
    // A case per driver: the "drivers" setting as an axis (before the backends).
    if (settings.contains("drivers") && !axes.contains("driver")) {
      const ojson& list = settings["drivers"];
      if (!list.is_array() || list.empty())
        throw InputError(gwhere + ": \"drivers\" must be a non-empty list of driver names");
      for (const auto& v : list)
        if (!v.is_string()) throw InputError(gwhere + ": \"drivers\" holds names (strings)");
      axes["driver"] = list;
    }
    settings.erase("drivers");
    // A case per backend: the axis, else the "backend" or "backends" setting.
    if (!axes.contains("backend")) {
      if (settings.contains("backend")) {
        axes["backend"] = ojson::array({settings["backend"]});
      } else {
        try {
          parseBackendList(settings["backends"]);
        } catch (const InputError& e) {
          throw InputError(gwhere + ": " + e.what());
        }
        axes["backend"] = settings["backends"];
      }
    }
    suite.groups.push_back(
        {{"name", name}, {"description", g.value("description", "")}, {"axes", axes}});

    for (const ojson& combo : combinations(axes)) {
      ojson s = settings;
      std::string params;
      for (const auto& [axis, value] : combo.items()) {
        if (axis.find('.') != std::string::npos)
          setSpecOption(s, axis, value, gwhere);
        else
          s[axis] = value;
        params += (params.empty() ? "" : ",") + axis + "=" + valueText(value);
      }
      SweepCase c;
      c.group = name;
      c.id = name + "/" + params;
      c.params = combo;
      c.index = static_cast<int>(suite.cases.size());
      c.stem = caseStem(c.id);
      c.request = toRequest(s, gwhere + ", case " + c.id);
      if (!ids.insert(c.id).second) throw InputError(gwhere + ": case " + c.id + " appears twice");
      suite.cases.push_back(std::move(c));
    }
  }
  return suite;
}

Suite loadSuite(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError("suite " + path + ": no such file");
  return parseSuite(readTextFile(path), path);
}

}  // namespace sb
