#include "harness/suite.h"

#include <cstdint>
#include <set>

#include "harness/json_keys.h"
#include "reports/files.h"
#include "reports/json_file.h"
#include "scenes/options.h"
#include "techniques/common/technique.h"

namespace sb {

namespace {

using ojson = nlohmann::ordered_json;

const std::vector<std::string> kSuiteKeys = {"name",    "description", "defaults",
                                             "presets", "groups",      "tables"};
const std::vector<std::string> kGroupKeys = {"name", "description", "preset", "axes"};
const std::vector<std::string> kSettings = {
    "scene",     "shadow", "oit",        "size",           "primitive",       "ribbon_width",
    "repeat",    "warmup", "reference",  "image",          "backends",        "backend",
    "platform",  "probe",  "camera_eye", "camera_target",  "camera_up",       "fov",
    "near",      "far",    "light",      "light_position", "light_direction", "light_intensity",
    "invariants"};
const std::vector<std::string> kSpecSettings = {"scene", "shadow", "oit"};

// An axis or setting value as text: strings as they are, numbers as JSON writes them.
std::string valueText(const ojson& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// Settings layered in order: later keys win.
void overlay(ojson& settings, const ojson& layer, const std::string& where) {
  for (const auto& [key, value] : layer.items()) {
    if (std::find(kSettings.begin(), kSettings.end(), key) == kSettings.end())
      throw InputError(where + ": " + unknownNameMessage("setting", key, kSettings));
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
  const std::string base = settings.contains(setting) ? valueText(settings[setting])
                           : setting == "scene"       ? "straight"
                                                      : "none";
  Spec spec = Spec::parse(base);
  spec.options[option] = valueText(value);
  settings[setting] = spec.str();
}

template <typename T>
T get(const ojson& settings, const std::string& key, const std::string& where) {
  try {
    return settings.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(where + ": setting '" + key + "' has the wrong type (" +
                     settings.at(key).dump() + ")");
  }
}

RenderRequest toRequest(const ojson& s, const std::string& where) {
  RenderRequest r;
  auto text = [&](const char* key) { return valueText(s.at(key)); };
  if (s.contains("scene")) r.scene = text("scene");
  if (s.contains("shadow")) r.shadow = text("shadow");
  if (s.contains("oit")) r.oit = text("oit");
  if (s.contains("size")) {
    const std::string size =
        s["size"].is_number_integer() ? text("size") + "x" + text("size") : text("size");
    std::tie(r.width, r.height) = parseSize(size);
  }
  if (s.contains("primitive")) r.primitive = text("primitive");
  if (s.contains("ribbon_width")) r.ribbonWidth = get<float>(s, "ribbon_width", where);
  if (s.contains("repeat")) r.repeat = get<int>(s, "repeat", where);
  if (s.contains("warmup")) r.warmup = get<int>(s, "warmup", where);
  if (s.contains("reference")) r.reference = get<bool>(s, "reference", where);
  if (s.contains("image")) r.image = get<bool>(s, "image", where);
  if (s.contains("invariants")) r.invariants = get<bool>(s, "invariants", where);
  r.backend = text("backend");
  if (r.backend != "gl" && r.backend != "vulkan")
    throw InputError(where + ": " + unknownNameMessage("backend", r.backend, {"gl", "vulkan"}));
  if (s.contains("platform")) r.platform = text("platform");
  if (s.contains("probe")) {
    const ojson& p = s["probe"];
    checkKeys(p, {"texel", "map_size", "samples"}, where + ": probe", "probe setting");
    ProbeSpec probe;
    try {
      if (p.contains("texel")) {
        const auto t = p["texel"].get<std::vector<uint32_t>>();
        if (t.size() != 2) throw InputError(where + ": probe texel must be [x, y]");
        probe.texel = {t[0], t[1]};
      }
      if (p.contains("map_size")) probe.mapSize = p["map_size"].get<uint32_t>();
      if (p.contains("samples")) probe.samples = p["samples"].get<int>();
    } catch (const nlohmann::json::exception&) {
      throw InputError(where + ": probe: texel [x, y], map_size and samples are numbers");
    }
    r.probe = probe;
  }
  ViewOverrides& v = r.view;
  auto vec = [&](const char* key) -> std::optional<glm::vec3> {
    if (!s.contains(key)) return std::nullopt;
    return parseVec3(text(key), where + ": " + key);
  };
  auto num = [&](const char* key) -> std::optional<float> {
    if (!s.contains(key)) return std::nullopt;
    return get<float>(s, key, where);
  };
  v.cameraEye = vec("camera_eye");
  v.cameraTarget = vec("camera_target");
  v.cameraUp = vec("camera_up");
  v.fov = num("fov");
  v.nearPlane = num("near");
  v.farPlane = num("far");
  if (s.contains("light")) v.lightType = text("light");
  v.lightPosition = vec("light_position");
  v.lightDirection = vec("light_direction");
  v.lightIntensity = num("light_intensity");
  if (r.repeat < 1) throw InputError(where + ": repeat must be at least 1");
  if (r.warmup < 0) throw InputError(where + ": warmup must be at least 0");
  if (!r.image && !r.reference)
    throw InputError(where +
                     ": \"image\": false measures only the visibility error: it needs "
                     "\"reference\": true");
  // Technique specs are checked now, not half way through a sweep.
  makeShadowTechnique(Spec::parse(r.shadow));
  makeOitTechnique(Spec::parse(r.oit));
  const Spec scene = Spec::parse(r.scene);
  std::vector<std::string> scenes;
  for (const auto& info : sceneCatalog()) scenes.push_back(info.name);
  if (std::find(scenes.begin(), scenes.end(), scene.name) == scenes.end())
    throw InputError(where + ": " + unknownNameMessage("scene", scene.name, scenes));
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
  if (!d.contains("name") || !d["name"].is_string())
    throw InputError(where + ": \"name\" (a string) is required");
  suite.name = d["name"];
  suite.description = d.value("description", "");
  if (!d.contains("groups") || !d["groups"].is_array() || d["groups"].empty())
    throw InputError(where + ": \"groups\" must be a non-empty array");
  const ojson presets = d.value("presets", ojson::object());
  if (!presets.is_object()) throw InputError(where + ": \"presets\" must be an object");

  ojson base = {{"backends", {"gl", "vulkan"}}};
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
    for (const auto& [axis, values] : axes.items()) {
      if (!values.is_array() || values.empty())
        throw InputError(gwhere + ": axis '" + axis + "' needs a non-empty array of values");
      if (axis.find('.') == std::string::npos &&
          std::find(kSettings.begin(), kSettings.end(), axis) == kSettings.end())
        throw InputError(gwhere + ": " + unknownNameMessage("axis", axis, kSettings));
    }
    if (!axes.contains("backend")) {
      if (!settings["backends"].is_array() || settings["backends"].empty())
        throw InputError(gwhere + ": \"backends\" must be a non-empty list");
      axes["backend"] = settings["backends"];
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
