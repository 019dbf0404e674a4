#include "harness/settings.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <sstream>

#include "backends/driver_env.h"
#include "base/options.h"
#include "harness/json_keys.h"
#include "harness/reference_spec.h"
#include "harness/setting_values.h"
#include "harness/technique_list.h"

namespace sb {

namespace {

using namespace setting_values;

// ------------------------------------------------------------------ the table

// "exact or aa:samples=1..8": the references and their options.
std::string referenceNames() {
  std::vector<std::string> names;
  for (const ReferenceDescriptor* k : referenceCatalog()) {
    std::string n = k->name;
    for (const OptionInfo& o : k->options)
      n += (n == k->name ? ":" : ",") + o.name + "=" + optionRange(o, "|");
    names.push_back(n);
  }
  return joinOr(names);
}

// The settings' example of a reference spec: the first further reference's own (a cheap one).
std::string referenceExample() {
  for (const ReferenceDescriptor* k : referenceCatalog())
    if (!k->isDefault) return k->example.empty() ? k->name : k->example;
  return defaultReference().name;
}

// A misspelt reference: the example's name with its last letter doubled.
std::string misspeltReference() {
  const std::string example = referenceExample();
  const std::string name = example.substr(0, example.find(':'));
  return name + name.back();
}

// Accessors of common field kinds.
template <typename T>
void plain(Setting& s, T RenderRequest::*field) {
  s.get = [field](const RenderRequest& r) { return ojson(r.*field); };
  s.set = [field](RenderRequest& r, const ojson& v) { r.*field = v.get<T>(); };
}

void plainFloat(Setting& s, float RenderRequest::*field) {
  s.get = [field](const RenderRequest& r) { return ojson(double(r.*field)); };
  s.set = [field](RenderRequest& r, const ojson& v) {
    r.*field = static_cast<float>(v.get<double>());
  };
}

void viewVec3(Setting& s, std::optional<glm::vec3> ViewOverrides::*field) {
  s.get = [field](const RenderRequest& r) {
    return (r.view.*field) ? vec3Json(*(r.view.*field)) : ojson(nullptr);
  };
  s.set = [field](RenderRequest& r, const ojson& v) { r.view.*field = jsonVec3(v); };
}

void viewFloat(Setting& s, std::optional<float> ViewOverrides::*field) {
  s.get = [field](const RenderRequest& r) {
    return (r.view.*field) ? ojson(double(*(r.view.*field))) : ojson(nullptr);
  };
  s.set = [field](RenderRequest& r, const ojson& v) {
    r.view.*field = static_cast<float>(v.get<double>());
  };
}

struct Range {
  double min, max;
  bool hasMin, hasMax, minOpen, maxOpen;
};
constexpr Range kAtLeast0 = {0, 0, true, false, false, false};
constexpr Range kAtLeast1 = {1, 0, true, false, false, false};
constexpr Range kPositive = {0, 0, true, false, true, false};

Setting make(std::string key, std::string flag, SettingType type, std::string defaultText,
             std::string help, std::string example, std::string bad) {
  Setting s;
  s.key = std::move(key);
  s.flag = std::move(flag);
  s.type = type;
  s.defaultText = std::move(defaultText);
  s.help = std::move(help);
  s.example = std::move(example);
  s.badExample = std::move(bad);
  return s;
}

Setting ranged(Setting s, const Range& r) {
  s.min = r.min;
  s.max = r.max;
  s.hasMin = r.hasMin;
  s.hasMax = r.hasMax;
  s.minOpen = r.minOpen;
  s.maxOpen = r.maxOpen;
  return s;
}

std::vector<Setting> buildTable() {
  using T = SettingType;
  std::vector<Setting> t;
  auto add = [&](Setting s) -> Setting& { return t.emplace_back(std::move(s)); };

  plain(add(make("scene", "--scene", T::Spec, "straight", "scene spec NAME:key=value,...",
                 "curly:strands=50,seed=7", "curli")),
        &RenderRequest::scene);
  // The techniques' names, defaults and examples come from their descriptors
  // (render/common/unit.h); a misspelling is an example's name doubled at its end.
  auto technique = [&](const char* key, const char* flag, Family f, const std::string& what) {
    const std::string example = exampleSpec(f);
    const std::string name = example.substr(0, example.find(':'));
    return make(key, flag, T::Spec, defaultTechnique(f).name,
                what + " spec NAME:option=value,...: " + joinOr(techniqueNames(f)) +
                    " (`strandbench list " + name + "`: its options)",
                example, name + name.back());
  };
  plain(add(technique("shadow", "--shadow", Family::Shadow, "shadow technique")),
        &RenderRequest::shadow);
  plain(add(technique("oit", "--oit", Family::Transparency, "transparency technique")),
        &RenderRequest::oit);
  plain(add(technique("shading", "--shading", Family::Shading, "hair shading model")),
        &RenderRequest::shading);
  {
    Setting& s = add(make("backend", "--backend", T::Enum, defaultBackend(),
                          "graphics API; suites and manifests also take `backends`, a list: one "
                          "case per backend",
                          backendNames().back(), backendNames().back() + "x"));
    s.choices = backendNames();
    plain(s, &RenderRequest::backend);
  }
  {
    // A process runs one driver (its loaders read the environment once), so the
    // setting names the process's driver; --driver on the command line re-executes
    // the process with another before anything loads (cli/main.cpp).
    Setting& s = add(
        make("driver", "--driver", T::String,
             "the process's (system unless the command line's --driver)",
             std::string(kDriverHelp) + "; in suites and manifests it must be the process's driver",
             "system", "no-such-driver"));
    s.get = [](const RenderRequest& r) {
      return r.driver.empty() ? ojson(nullptr) : ojson(r.driver);
    };
    s.set = [](RenderRequest& r, const ojson& v) { r.driver = v.get<std::string>(); };
  }
  {
    // The example is osmesa (headless): a window platform needs a display.
    Setting& s = add(make("platform", "--platform", T::String, "the backend's first",
                          "the backend's platform; window: a GLFW window, each timed frame "
                          "presented (needs a display)",
                          platformNames(defaultBackend()).at(1), "no-such-platform"));
    s.get = [](const RenderRequest& r) {
      return r.platform.empty() ? ojson(nullptr) : ojson(r.platform);
    };
    s.set = [](RenderRequest& r, const ojson& v) { r.platform = v.get<std::string>(); };
  }
  {
    Setting& s =
        add(make("size", "--size", T::Size, "512x512",
                 "image size WIDTHxHEIGHT (in JSON also a number N for NxN)", "40x24", "0x0"));
    s.get = [](const RenderRequest& r) { return ojson::array({r.width, r.height}); };
    s.set = [](RenderRequest& r, const ojson& v) {
      r.width = v[0].get<uint32_t>();
      r.height = v[1].get<uint32_t>();
    };
  }
  {
    Setting& s =
        add(make("primitive", "--primitive", T::Enum, "lines",
                 "strands drawn as lines, camera-facing ribbons (--ribbon-width pixels) or "
                 "ribbons of their world width with analytic coverage",
                 "ribbons", "points"));
    s.choices = {"lines", "ribbons", "world"};
    plain(s, &RenderRequest::primitive);
  }
  {
    Setting& s = add(make("geometry", "--geometry", T::Enum, "cpu",
                          "where the strands are made (docs/geometry.md): cpu (expanded on the "
                          "CPU and uploaded), compute (made from the scene's groom, guides= or "
                          "instances=, by a compute pass on the device), mesh (made from the groom "
                          "in mesh shaders as they are drawn: Vulkan with VK_EXT_mesh_shader, "
                          "e.g. --driver mesa-25.0)",
                          "compute", "gpu"));
    s.choices = {"cpu", "compute", "mesh"};
    plain(s, &RenderRequest::geometry);
  }
  plainFloat(add(ranged(make("ribbon_width", "--ribbon-width", T::Float, "1",
                             "ribbon width in pixels", "2.5", "0"),
                        {0, 64, true, true, true, false})),
             &RenderRequest::ribbonWidth);
  {
    // Scene-wide anti-aliasing: the mesh and hair colour passes render with N
    // samples and are resolved before the composite. Techniques with per-pixel
    // data that is not multisampled refuse N > 1; the reference stays at one
    // sample (exact at pixel centres). The device's counts are checked when it
    // is made.
    Setting& s = add(make("msaa", "--msaa", T::Enum, "1",
                          "samples per pixel of the frame (anti-aliasing): 1, 2, 4, 8, as the "
                          "device supports; multisampled: --oit " +
                              joinOr(techniqueNames(Family::Transparency,
                                                    [](const TechniqueDescriptor& d) {
                                                      return d.caps.multisampling;
                                                    })),
                          "4", "3"));
    s.choices = {"1", "2", "4", "8"};
    s.get = [](const RenderRequest& r) { return ojson(std::to_string(r.msaa)); };
    s.set = [](RenderRequest& r, const ojson& v) { r.msaa = std::stoi(v.get<std::string>()); };
  }
  plain(add(ranged(make("repeat", "--repeat", T::Int, "1", "timed frames", "3", "0"), kAtLeast1)),
        &RenderRequest::repeat);
  plain(add(ranged(make("warmup", "--warmup", T::Int, "1 (manifests: 0)",
                        "untimed frames before the timed ones", "2", "-1"),
                   kAtLeast0)),
        &RenderRequest::warmup);
  {
    // A flag that may take a reference spec, given more than once: bare, the
    // default (exact) reference; `--reference aa:samples=4` adds the anti-aliased
    // one (harness/reference_spec.h), and the default is rendered with it.
    Setting& s = add(make(
        "reference", "--reference", T::References, "false",
        "also render the reference (exact shadows and transparency) and report the error against "
        "it; --reference SPEC (more than once) adds another reference, its error under "
        "error.<name>: " +
            referenceNames() + " (the default reference is always rendered with them)",
        referenceExample(), misspeltReference()));
    s.get = [](const RenderRequest& r) -> ojson {
      if (r.references.empty()) return r.reference;
      ojson list = ojson::array({"exact"});
      for (const std::string& spec : r.references) list.push_back(spec);
      return list;
    };
    s.set = [](RenderRequest& r, const ojson& v) {
      r.references.clear();
      if (v.is_boolean()) {
        r.reference = v.get<bool>();
        return;
      }
      r.reference = true;
      for (const ojson& spec : v)
        if (spec.get<std::string>() != "exact") r.references.push_back(spec.get<std::string>());
    };
  }
  plain(add(make("image", "--no-image", T::Flag, "true",
                 "shade the image; false (--no-image): only the visibility error (needs the "
                 "reference)",
                 "false", "maybe")),
        &RenderRequest::image);
  {
    Setting& s = add(make("probe", "--probe", T::Probe, "none",
                          "also report visibility along the light ray through texel X,Y of a "
                          "MAP_SIZE map (default 512), at SAMPLES depths (default 256)",
                          "12,10,24,8", "600,1"));
    s.get = [](const RenderRequest& r) -> ojson {
      if (!r.probe) return nullptr;
      return {{"texel", {r.probe->texel.x, r.probe->texel.y}},
              {"map_size", r.probe->mapSize},
              {"samples", r.probe->samples}};
    };
    s.set = [](RenderRequest& r, const ojson& v) {
      ProbeSpec p;
      p.texel = {v["texel"][0].get<uint32_t>(), v["texel"][1].get<uint32_t>()};
      p.mapSize = v["map_size"].get<uint32_t>();
      p.samples = v["samples"].get<int>();
      r.probe = p;
    };
  }
  {
    Setting& s = add(make("animate", "--animate", T::Animation, "none",
                          "also render frames=N frames (default 8) of a light or camera orbit of "
                          "degrees=D (default 30) by the technique and the reference: per-frame "
                          "errors and the flicker error (needs the reference)",
                          "camera-orbit:frames=3,degrees=12", "light-orbit:frames=1"));
    s.get = [](const RenderRequest& r) -> ojson {
      if (!r.animate) return nullptr;
      return {{"kind", r.animate->kind},
              {"frames", r.animate->frames},
              {"degrees", r.animate->degrees}};
    };
    s.set = [](RenderRequest& r, const ojson& v) {
      r.animate = AnimateSpec{v["kind"].get<std::string>(), v["frames"].get<int>(),
                              v["degrees"].get<double>()};
    };
  }
  plain(add(make("invariants", "--invariants", T::Flag, "false",
                 "check the outputs and maps (finite, in range; needs the reference)", "true",
                 "maybe")),
        &RenderRequest::invariants);
  plain(add(make("run_to_run", "--no-run-to-run", T::Flag, "true",
                 "sweeps with invariants: run each case again on a fresh device and require "
                 "identical outputs and work counters; false (--no-run-to-run): once",
                 "false", "maybe")),
        &RenderRequest::runToRun);
  plain(add(make("validation", "--validation", T::Flag, "false",
                 "Vulkan validation layers on (messages counted)", "true", "maybe")),
        &RenderRequest::validation);
  {
    Setting& s = add(ranged(make("memory_limit", "--memory-limit", T::Int, "none",
                                 "refuse the run, before its resources are made, when they would "
                                 "take more bytes than this",
                                 "1000000000", "0"),
                            kAtLeast1));
    s.get = [](const RenderRequest& r) {
      return r.memoryLimit > 0 ? ojson(r.memoryLimit) : ojson(nullptr);
    };
    s.set = [](RenderRequest& r, const ojson& v) { r.memoryLimit = v.get<long long>(); };
  }
  viewVec3(add(make("camera_eye", "--camera-eye", T::Vec3, "fitted to the scene",
                    "camera position x,y,z", "0.3,1.2,4", "1,2")),
           &ViewOverrides::cameraEye);
  viewVec3(add(make("camera_target", "--camera-target", T::Vec3, "fitted to the scene",
                    "point the camera looks at", "0,0.2,0", "0,x,0")),
           &ViewOverrides::cameraTarget);
  {
    Setting& s = add(make("camera_up", "--camera-up", T::Vec3, "0,1,0", "camera up direction",
                          "1,1,0", "0,0,0"));
    s.nonZero = true;
    viewVec3(s, &ViewOverrides::cameraUp);
  }
  viewFloat(add(ranged(make("fov", "--fov", T::Float, "fitted to the scene",
                            "vertical field of view in degrees", "60", "180"),
                       {0, 180, true, true, true, true})),
            &ViewOverrides::fov);
  viewFloat(add(ranged(make("near", "--near", T::Float, "fitted to the scene",
                            "camera near plane distance", "0.5", "0"),
                       kPositive)),
            &ViewOverrides::nearPlane);
  viewFloat(add(ranged(make("far", "--far", T::Float, "fitted to the scene",
                            "camera far plane distance", "50", "-1"),
                       kPositive)),
            &ViewOverrides::farPlane);
  {
    Setting& s =
        add(make("light", "--light", T::Enum, "directional", "light type", "point", "spot"));
    s.choices = {"directional", "point"};
    s.get = [](const RenderRequest& r) {
      return r.view.lightType ? ojson(*r.view.lightType) : ojson(nullptr);
    };
    s.set = [](RenderRequest& r, const ojson& v) { r.view.lightType = v.get<std::string>(); };
  }
  viewVec3(
      add(make("light_position", "--light-position", T::Vec3, "fitted to the scene",
               "light position x,y,z (directional: where its frustum starts)", "2,3,4", "2,3")),
      &ViewOverrides::lightPosition);
  {
    Setting& s = add(make("light_direction", "--light-direction", T::Vec3, "fitted to the scene",
                          "direction the light travels x,y,z", "-1,-0.5,0", "0,0,0"));
    s.nonZero = true;
    viewVec3(s, &ViewOverrides::lightDirection);
  }
  viewVec3(add(make("light_color", "--light-color", T::Vec3, "1,1,1", "light colour r,g,b",
                    "1,0.5,0.25", "1,0.5")),
           &ViewOverrides::lightColor);
  viewFloat(add(ranged(make("light_intensity", "--light-intensity", T::Float, "1",
                            "light intensity", "2", "-1"),
                       kAtLeast0)),
            &ViewOverrides::lightIntensity);
  {
    Setting& s = add(make("extra_lights", "--extra-lights", T::Lights, "none",
                          "lights beside the key light, each with its own instance of the shadow "
                          "technique; the image sums their shading",
                          "point:1,2,3:1,0.9,0.8:0.5;directional:1,-1,0", "spot:1,2,3"));
    s.get = [](const RenderRequest& r) -> ojson {
      if (r.extraLights.empty()) return nullptr;
      ojson lights = ojson::array();
      for (const ExtraLight& l : r.extraLights)
        lights.push_back(lightJson(l.type, vec3Json(l.at), vec3Json(l.color), l.intensity));
      return lights;
    };
    s.set = [](RenderRequest& r, const ojson& v) {
      r.extraLights.clear();
      for (const ojson& l : v) {
        const std::string type = l["type"].get<std::string>();
        r.extraLights.push_back({type, jsonVec3(l[type == "point" ? "position" : "direction"]),
                                 jsonVec3(l["color"]),
                                 static_cast<float>(l["intensity"].get<double>())});
      }
    };
  }
  return t;
}

}  // namespace

namespace {
// Per SettingType, in the enum's order: the name in docs and `list`, and the
// value's shape in --help.
struct TypeNames {
  const char* name;
  const char* cli;
};
constexpr TypeNames kTypeNames[] = {
    {"spec", "SPEC"},
    {"string", "NAME"},
    {"enum", "NAME"},
    {"int", "INT"},
    {"float", "NUMBER"},
    {"vec3", "X,Y,Z"},
    {"flag", "NAME"},
    {"size", "WxH"},
    {"probe", "X,Y[,MAP[,SAMPLES]]"},
    {"animation", "KIND[:frames=N,degrees=D]"},
    {"lights", "TYPE:X,Y,Z[:R,G,B[:I]];..."},
    {"references", "[SPEC]"},
};
static_assert(std::size(kTypeNames) == static_cast<std::size_t>(SettingType::References) + 1);
const TypeNames& typeNames(SettingType t) { return kTypeNames[static_cast<std::size_t>(t)]; }
}  // namespace

std::string Setting::typeName() const { return typeNames(type).name; }

std::string Setting::rangeText() const {
  switch (type) {
    case SettingType::Enum:
      return joinOr(choices);
    case SettingType::Int:
    case SettingType::Float:
      if (hasMin && hasMax)
        return (type == SettingType::Int ? numberText(min) + ".." + numberText(max)
                                         : std::string(minOpen ? "(" : "[") + numberText(min) +
                                               ", " + numberText(max) + (maxOpen ? ")" : "]"));
      if (hasMin)
        return type == SettingType::Int ? "at least " + numberText(min)
                                        : std::string(minOpen ? "> " : ">= ") + numberText(min);
      if (hasMax) return std::string(maxOpen ? "< " : "<= ") + numberText(max);
      return "";
    case SettingType::Vec3:
      return nonZero ? "non-zero" : "";
    case SettingType::Size:
      return "1.." + std::to_string(kMaxSize) + " each";
    case SettingType::Probe:
      return "texel inside the map; map 1.." + std::to_string(kMaxSize) + "; samples 2.." +
             std::to_string(kMaxSamples);
    case SettingType::Animation:
      return "light-orbit or camera-orbit; frames 2.." + std::to_string(kMaxFrames) +
             "; degrees [-360, 360]";
    case SettingType::Lights:
      return "0.." + std::to_string(kMaxExtraLights) + " lights, directional or point";
    case SettingType::References:
      return "true, false or specs: " + referenceNames();
    case SettingType::Spec:
      return key == "scene" ? "a scene of `strandbench list`" : "a technique of `strandbench list`";
    case SettingType::String:
      if (key == "platform") {
        std::string s;
        for (const auto& b : backendCatalog())
          for (const auto& p : b.platforms) s += (s.empty() ? "" : ", ") + p + " (" + b.name + ")";
        return s;
      }
      return "";
    case SettingType::Flag:
      return "";
  }
  return "";
}

const std::vector<Setting>& settingsTable() {
  static const std::vector<Setting> table = buildTable();
  return table;
}

const Setting* findSetting(const std::string& key) {
  for (const Setting& s : settingsTable())
    if (s.key == key) return &s;
  return nullptr;
}

std::vector<std::string> settingKeys() {
  std::vector<std::string> keys;
  for (const Setting& s : settingsTable()) keys.push_back(s.key);
  return keys;
}

std::vector<std::string> viewSettingKeys() {
  std::vector<std::string> keys = settingKeys();
  keys.erase(keys.begin(), std::find(keys.begin(), keys.end(), "camera_eye"));
  return keys;
}

std::string settingLabel(const Setting& s, Spelling spelling) {
  return spelling == Spelling::Cli ? s.flag : "\"" + s.key + "\"";
}

std::string settingMessage(const Setting& s, Spelling spelling, const std::string& text,
                           const std::string& problem) {
  return settingLabel(s, spelling) + " " + (spelling == Spelling::Cli ? text : "'" + text + "'") +
         ": " + problem;
}

void setFromText(RenderRequest& req, const Setting& s, const std::string& text) {
  try {
    const ojson v = fromText(s, text);
    checkValue(s, v);
    s.set(req, v);
  } catch (const Problem& p) {
    throw InputError(s.flag + " " + text + ": " + p.what);
  }
}

void setFromJson(RenderRequest& req, const Setting& s, const ojson& value) {
  try {
    const ojson v = fromJson(s, value);
    checkValue(s, v);
    s.set(req, v);
  } catch (const Problem& p) {
    throw InputError(settingLabel(s, Spelling::Json) + " " + jsonShown(value) + ": " + p.what);
  }
}

std::string settingText(const RenderRequest& req, const Setting& s) {
  return textOf(s, s.get(req));
}

void checkRequest(const RenderRequest& req, Spelling spelling) {
  for (const Setting& s : settingsTable()) {
    const ojson v = s.get(req);
    if (v.is_null()) continue;
    try {
      checkValue(s, v);
    } catch (const Problem& p) {
      throw InputError(settingMessage(s, spelling, textOf(s, v), p.what));
    }
  }
  try {
    if (!req.driver.empty() && !isCurrentDriver(req.driver))
      throw InputError("this process runs driver '" + currentDriver() +
                       "' and one process loads one driver: give --driver " + req.driver +
                       " on the command line");
  } catch (const InputError& e) {
    throw InputError(settingMessage(*findSetting("driver"), spelling, req.driver, e.what()));
  }
  if (!req.platform.empty()) {
    const std::vector<std::string> platforms = platformNames(req.backend);
    if (std::find(platforms.begin(), platforms.end(), req.platform) == platforms.end())
      throw InputError(
          settingMessage(*findSetting("platform"), spelling, req.platform,
                         unknownChoice(req.backend + " platform", req.platform, platforms)));
  }
  // A flag as the front end turns it on or off: "--reference", "\"reference\": true".
  auto flag = [&](const char* key, bool value) {
    const Setting& s = *findSetting(key);
    return spelling == Spelling::Cli
               ? s.flag
               : settingLabel(s, spelling) + ": " + (value ? "true" : "false");
  };
  if (!req.image && !req.reference)
    throw InputError(flag("image", false) + " measures only the visibility error: it needs " +
                     flag("reference", true));
  if (!req.references.empty() && !req.image)
    throw InputError(settingMessage(
        *findSetting("reference"), spelling, settingText(req, *findSetting("reference")),
        "the further references are images: drop " + flag("image", false)));
  if (req.animate && !req.reference)
    throw InputError(settingLabel(*findSetting("animate"), spelling) +
                     " compares every frame with the reference: it needs " +
                     flag("reference", true));
  if (req.invariants && !req.reference)
    throw InputError(flag("invariants", true) + " checks against the reference: it needs " +
                     flag("reference", true));
}

std::vector<std::string> parseBackendList(const ojson& value) {
  if (!value.is_array() || value.empty())
    throw InputError("\"backends\" " + jsonShown(value) + ": expected a non-empty list of " +
                     joinOr(backendNames()));
  const std::vector<std::string> names = backendNames();
  std::vector<std::string> out;
  for (const ojson& b : value) {
    if (!b.is_string())
      throw InputError("\"backends\" entry " + b.dump() + ": expected " + joinOr(names));
    const std::string name = b.get<std::string>();
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InputError("\"backends\" entry '" + name +
                       "': " + unknownChoice("backend", name, names));
    if (std::find(out.begin(), out.end(), name) != out.end())
      throw InputError("\"backends\" lists '" + name + "' twice");
    out.push_back(name);
  }
  return out;
}

// ------------------------------------------------------------------ the CLI

namespace {}  // namespace

CliSettings::CliSettings(CLI::App& cmd, const std::vector<std::string>& keys,
                         const RenderRequest& defaults) {
  for (const std::string& k : keys)
    if (!findSetting(k)) throw std::logic_error("no setting '" + k + "'");
  // The driver goes with the backend: every command that takes --backend takes --driver.
  const bool withDriver = std::find(keys.begin(), keys.end(), "backend") != keys.end();
  for (const Setting& s : settingsTable()) {
    if (!keys.empty() && std::find(keys.begin(), keys.end(), s.key) == keys.end() &&
        !(withDriver && s.key == "driver"))
      continue;
    Entry e{&s, nullptr, std::make_shared<std::string>(), std::make_shared<bool>(false),
            std::make_shared<std::vector<std::string>>()};
    if (s.type == SettingType::Flag) {
      e.option = cmd.add_flag(s.flag, *e.flag, s.help);
    } else if (s.type == SettingType::References) {
      // Bare (an empty value) or with a spec, as often as wanted.
      e.option = cmd.add_option(s.flag, *e.texts, s.help + " (" + s.rangeText() + ")")
                     ->expected(0, 1)
                     ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
      e.option->type_name(typeNames(s.type).cli);
    } else {
      const std::string shownDefault = settingText(defaults, s);
      const std::string range = s.rangeText();
      e.option =
          cmd.add_option(s.flag, *e.text, s.help + (range.empty() ? "" : " (" + range + ")"));
      e.option->default_str(shownDefault.empty() ? s.defaultText : shownDefault);
      e.option->type_name(typeNames(s.type).cli);
    }
    entries_.push_back(std::move(e));
  }
}

void CliSettings::apply(RenderRequest& req) const {
  for (const Entry& e : entries_) {
    if (e.option->count() == 0) continue;
    const Setting& s = *e.setting;
    if (s.type == SettingType::Flag) {
      const bool clears = s.flag.rfind("--no-", 0) == 0;
      s.set(req, *e.flag != clears);
    } else if (s.type == SettingType::References) {
      // Each occurrence checked alone (its message names it), then all together.
      std::string all;
      for (const std::string& t : *e.texts) {
        RenderRequest scratch = req;
        setFromText(scratch, s, t.empty() ? "exact" : t);
        all += (all.empty() ? "" : ";") + (t.empty() ? std::string("exact") : t);
      }
      setFromText(req, s, all);
    } else {
      setFromText(req, s, *e.text);
    }
  }
  checkRequest(req, Spelling::Cli);
}

// ------------------------------------------------------------------ documentation

std::string settingsMarkdown() {
  std::string md =
      "| key (suites, manifests) | CLI | type | range or choices | default | what |\n"
      "|---|---|---|---|---|---|\n";
  auto cell = [](std::string s) {
    for (std::size_t p = 0; (p = s.find('|', p)) != std::string::npos; p += 2)
      s.replace(p, 1, "\\|");
    return s;
  };
  for (const Setting& s : settingsTable())
    md += "| `" + s.key + "` | `" + s.flag + "` | " + s.typeName() + " | " + cell(s.rangeText()) +
          " | " + cell(s.defaultText) + " | " + cell(s.help) + " |\n";
  return md;
}

std::string settingsText() {
  std::string out;
  for (const Setting& s : settingsTable()) {
    out += "  " + s.flag + " / \"" + s.key + "\"  " + s.typeName();
    const std::string range = s.rangeText();
    if (!range.empty()) out += " (" + range + ")";
    out += ", default " + s.defaultText + "  " + s.help + "\n";
  }
  return out;
}

nlohmann::json settingsJson() {
  nlohmann::json a = nlohmann::json::array();
  for (const Setting& s : settingsTable())
    a.push_back({{"key", s.key},
                 {"flag", s.flag},
                 {"type", s.typeName()},
                 {"range", s.rangeText()},
                 {"choices", s.choices},
                 {"default", s.defaultText},
                 {"help", s.help}});
  return a;
}

}  // namespace sb
