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

#include "harness/json_keys.h"
#include "scenes/options.h"

namespace sb {

namespace {

using ojson = nlohmann::ordered_json;

// A value's problem; the caller names the setting and the value.
struct Problem {
  std::string what;
};

std::string joinOr(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i == 0 ? "" : i + 1 == v.size() ? " or " : ", ") + v[i];
  return s;
}

// The shortest text that reads back as the same float (values are stored as floats).
std::string numberText(double d) {
  if (d == std::floor(d) && std::fabs(d) < 1e15) return std::to_string(static_cast<long long>(d));
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, d);
    if (static_cast<float>(std::strtod(buf, nullptr)) == static_cast<float>(d)) break;
  }
  return buf;
}

// Strict numbers: the whole text, finite.
std::optional<double> parseNumber(const std::string& t) {
  if (t.empty() || std::isspace(static_cast<unsigned char>(t[0]))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double d = std::strtod(t.c_str(), &end);
  if (*end != '\0' || errno == ERANGE || !std::isfinite(d)) return std::nullopt;
  return d;
}

std::optional<long long> parseInteger(const std::string& t) {
  long long v = 0;
  const char* first = t.data() + (t.size() > 1 && t[0] == '+' ? 1 : 0);
  const auto [ptr, ec] = std::from_chars(first, t.data() + t.size(), v);
  if (ec != std::errc() || ptr != t.data() + t.size() || t.empty()) return std::nullopt;
  return v;
}

// "a,b,c" -> the parts.
std::vector<std::string> splitCommas(const std::string& t) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = t.find(',', start);
    parts.push_back(t.substr(start, comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

ojson vec3Json(const glm::vec3& v) { return ojson::array({double(v.x), double(v.y), double(v.z)}); }
glm::vec3 jsonVec3(const ojson& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

constexpr uint32_t kMaxSize = 16384;
constexpr long long kMaxSamples = 1000000;
// Animation: every frame is rendered twice (technique and reference).
constexpr long long kMaxFrames = 1000;
constexpr double kMaxDegrees = 360;
const std::vector<std::string> kAnimationKinds = {"light-orbit", "camera-orbit"};
// Extra lights: the key light and these make at most 8, each with its own shadow maps.
constexpr std::size_t kMaxExtraLights = 7;
const std::vector<std::string> kLightTypes = {"directional", "point"};

// ------------------------------------------------------------------ text and JSON forms

ojson sizeFromText(const std::string& t) {
  unsigned long w = 0, h = 0;
  char x = 0;
  std::istringstream in(t);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !in.eof() ||
      t.find('-') != std::string::npos || t.find('+') != std::string::npos)
    throw Problem{"expected WIDTHxHEIGHT, e.g. 512x512"};
  return ojson::array({w, h});
}

ojson probeFromText(const std::string& t) {
  const std::vector<std::string> parts = splitCommas(t);
  std::vector<long long> v;
  for (const auto& p : parts)
    if (const auto n = parseInteger(p); n && *n >= 0) v.push_back(*n);
  if (v.size() != parts.size() || v.size() < 2 || v.size() > 4)
    throw Problem{"expected X,Y[,MAP_SIZE[,SAMPLES]] (a light texel, its map's size, samples)"};
  const ProbeSpec d;
  return {{"texel", {v[0], v[1]}},
          {"map_size", v.size() > 2 ? v[2] : d.mapSize},
          {"samples", v.size() > 3 ? v[3] : d.samples}};
}

ojson probeFromJson(const ojson& v) {
  try {
    checkKeys(v, {"texel", "map_size", "samples"}, "probe", "probe setting");
  } catch (const InputError& e) {
    throw Problem{std::string(e.what()).substr(std::string("probe: ").size())};
  }
  const ProbeSpec d;
  ojson p = {{"texel", {d.texel.x, d.texel.y}}, {"map_size", d.mapSize}, {"samples", d.samples}};
  if (v.contains("texel")) {
    const ojson& t = v["texel"];
    if (!t.is_array() || t.size() != 2 || !t[0].is_number_integer() || !t[1].is_number_integer() ||
        t[0].get<long long>() < 0 || t[1].get<long long>() < 0)
      throw Problem{"texel must be [x, y], two integers >= 0"};
    p["texel"] = t;
  }
  for (const char* k : {"map_size", "samples"}) {
    if (!v.contains(k)) continue;
    if (!v[k].is_number_integer()) throw Problem{std::string(k) + " must be an integer"};
    p[k] = v[k];
  }
  return p;
}

ojson animationFromText(const std::string& t) {
  Spec spec;
  try {
    spec = Spec::parse(t);
  } catch (const InputError& e) {
    throw Problem{e.what()};
  }
  const AnimateSpec d;
  ojson a = {{"kind", spec.name}, {"frames", d.frames}, {"degrees", d.degrees}};
  for (const auto& [k, v] : spec.options) {
    if (k == "frames") {
      const auto n = parseInteger(v);
      if (!n) throw Problem{"frames '" + v + "': expected an integer"};
      a["frames"] = *n;
    } else if (k == "degrees") {
      const auto degrees = parseNumber(v);
      if (!degrees) throw Problem{"degrees '" + v + "': not a finite number"};
      a["degrees"] = *degrees;
    } else {
      throw Problem{"unknown option '" + k + "'; expected frames or degrees"};
    }
  }
  return a;
}

ojson animationFromJson(const ojson& v) {
  try {
    checkKeys(v, {"kind", "frames", "degrees"}, "animate", "animate setting");
  } catch (const InputError& e) {
    throw Problem{std::string(e.what()).substr(std::string("animate: ").size())};
  }
  const AnimateSpec d;
  ojson a = {{"kind", d.kind}, {"frames", d.frames}, {"degrees", d.degrees}};
  if (v.contains("kind")) {
    if (!v["kind"].is_string()) throw Problem{"kind must be a string"};
    a["kind"] = v["kind"];
  }
  if (v.contains("frames")) {
    if (!v["frames"].is_number_integer()) throw Problem{"frames must be an integer"};
    a["frames"] = v["frames"].get<long long>();
  }
  if (v.contains("degrees")) {
    if (!v["degrees"].is_number()) throw Problem{"degrees must be a number"};
    a["degrees"] = v["degrees"].get<double>();
  }
  return a;
}

// One extra light, canonical: {"type", "position" or "direction", "color", "intensity"}.
ojson lightJson(const std::string& type, const ojson& at, const ojson& color, double intensity) {
  return {{"type", type},
          {type == "point" ? "position" : "direction", at},
          {"color", color},
          {"intensity", intensity}};
}

ojson numbersFromText(const std::string& t, std::size_t count) {
  const std::vector<std::string> parts = splitCommas(t);
  ojson v = ojson::array();
  for (const auto& p : parts)
    if (const auto d = parseNumber(p)) v.push_back(*d);
  if (parts.size() != count || v.size() != count) return nullptr;
  return v;
}

// "TYPE:X,Y,Z[:R,G,B[:INTENSITY]]" -> one canonical light.
ojson lightFromText(const std::string& t) {
  const std::string shape =
      "expected TYPE:X,Y,Z[:R,G,B[:INTENSITY]] (X,Y,Z: a point light's position, a "
      "directional light's direction)";
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const std::size_t colon = t.find(':', start);
    parts.push_back(t.substr(start, colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() < 2 || parts.size() > 4) throw Problem{"'" + t + "': " + shape};
  const ojson at = numbersFromText(parts[1], 3);
  const ojson color = parts.size() > 2 ? numbersFromText(parts[2], 3) : ojson::array({1, 1, 1});
  const ojson intensity = parts.size() > 3 ? numbersFromText(parts[3], 1) : ojson::array({1});
  if (at.is_null() || color.is_null() || intensity.is_null())
    throw Problem{"'" + t + "': " + shape};
  return lightJson(parts[0], at, color, intensity[0].get<double>());
}

ojson lightsFromText(const std::string& t) {
  ojson lights = ojson::array();
  if (t.empty()) return lights;
  for (std::size_t start = 0;;) {
    const std::size_t semi = t.find(';', start);
    lights.push_back(lightFromText(t.substr(start, semi - start)));
    if (semi == std::string::npos) return lights;
    start = semi + 1;
  }
}

ojson lightFromJson(const ojson& v) {
  if (v.is_string()) return lightFromText(v.get<std::string>());
  if (!v.is_object())
    throw Problem{
        "each light is \"TYPE:X,Y,Z[:R,G,B[:INTENSITY]]\" or {\"type\", "
        "\"position\" | \"direction\", \"color\", \"intensity\"}"};
  try {
    checkKeys(v, {"type", "position", "direction", "color", "intensity"}, "light", "light");
  } catch (const InputError& e) {
    throw Problem{std::string(e.what()).substr(std::string("light: ").size())};
  }
  if (!v.contains("type") || !v["type"].is_string()) throw Problem{"a light needs a \"type\""};
  const std::string type = v["type"].get<std::string>();
  const char* where = type == "point" ? "position" : "direction";
  auto vec3 = [&](const char* key) -> ojson {
    const ojson& x = v[key];
    if (!x.is_array() || x.size() != 3 ||
        !std::all_of(x.begin(), x.end(), [](const ojson& n) { return n.is_number(); }))
      throw Problem{std::string("a light's \"") + key + "\" must be [x, y, z]"};
    return ojson::array({x[0].get<double>(), x[1].get<double>(), x[2].get<double>()});
  };
  if (!v.contains(where))
    throw Problem{"a " + type + " light needs \"" + where +
                  "\" (and no other of position, "
                  "direction)"};
  if (v.contains(type == "point" ? "direction" : "position"))
    throw Problem{std::string("a ") + type + " light takes \"" + where + "\" only"};
  if (v.contains("intensity") && !v["intensity"].is_number())
    throw Problem{"a light's \"intensity\" must be a number"};
  return lightJson(type, vec3(where), v.contains("color") ? vec3("color") : ojson::array({1, 1, 1}),
                   v.contains("intensity") ? v["intensity"].get<double>() : 1.0);
}

ojson fromText(const Setting& s, const std::string& t) {
  switch (s.type) {
    case SettingType::Spec:
      try {
        Spec::parse(t);
      } catch (const InputError& e) {
        throw Problem{e.what()};
      }
      return t;
    case SettingType::String:
    case SettingType::Enum:
      return t;
    case SettingType::Int:
      if (const auto n = parseInteger(t)) return *n;
      throw Problem{"expected an integer"};
    case SettingType::Float:
      if (const auto d = parseNumber(t)) return *d;
      throw Problem{"not a finite number"};
    case SettingType::Vec3: {
      const std::vector<std::string> parts = splitCommas(t);
      ojson v = ojson::array();
      for (const auto& p : parts)
        if (const auto d = parseNumber(p)) v.push_back(*d);
      if (parts.size() != 3 || v.size() != 3) throw Problem{"expected three finite numbers x,y,z"};
      return v;
    }
    case SettingType::Flag:
      if (t == "true") return true;
      if (t == "false") return false;
      throw Problem{"expected true or false"};
    case SettingType::Size:
      return sizeFromText(t);
    case SettingType::Probe:
      return probeFromText(t);
    case SettingType::Animation:
      return animationFromText(t);
    case SettingType::Lights:
      return lightsFromText(t);
  }
  return nullptr;
}

ojson fromJson(const Setting& s, const ojson& v) {
  switch (s.type) {
    case SettingType::Spec:
    case SettingType::String:
    case SettingType::Enum:
      if (!v.is_string()) throw Problem{"expected a string"};
      return fromText(s, v.get<std::string>());
    case SettingType::Int:
      if (!v.is_number_integer()) throw Problem{"expected an integer"};
      if (v.is_number_unsigned() &&
          v.get<unsigned long long>() >
              static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
        throw Problem{"too large"};
      return v.get<long long>();
    case SettingType::Float:
      if (!v.is_number()) throw Problem{"expected a number"};
      return v.get<double>();
    case SettingType::Vec3:
      if (v.is_string()) return fromText(s, v.get<std::string>());
      if (v.is_array() && v.size() == 3 &&
          std::all_of(v.begin(), v.end(), [](const ojson& x) { return x.is_number(); }))
        return ojson::array({v[0].get<double>(), v[1].get<double>(), v[2].get<double>()});
      throw Problem{"expected \"x,y,z\" or [x, y, z]"};
    case SettingType::Flag:
      if (!v.is_boolean()) throw Problem{"expected true or false"};
      return v;
    case SettingType::Size:
      if (v.is_string()) return fromText(s, v.get<std::string>());
      if (v.is_number_integer()) return ojson::array({v, v});
      throw Problem{"expected \"WIDTHxHEIGHT\" or a number N for NxN"};
    case SettingType::Probe:
      if (v.is_string()) return fromText(s, v.get<std::string>());
      if (v.is_object()) return probeFromJson(v);
      throw Problem{"expected {\"texel\": [x, y], \"map_size\": N, \"samples\": N} or \"X,Y\""};
    case SettingType::Animation:
      if (v.is_string()) return fromText(s, v.get<std::string>());
      if (v.is_object()) return animationFromJson(v);
      throw Problem{
          "expected \"KIND:frames=N,degrees=D\" or {\"kind\": ..., \"frames\": N, "
          "\"degrees\": D}"};
    case SettingType::Lights: {
      if (v.is_string()) return fromText(s, v.get<std::string>());
      if (!v.is_array()) throw Problem{"expected a list of lights or \"TYPE:X,Y,Z;...\""};
      ojson lights = ojson::array();
      for (const ojson& l : v) lights.push_back(lightFromJson(l));
      return lights;
    }
  }
  return nullptr;
}

// The CLI text of a canonical value.
std::string textOf(const Setting& s, const ojson& v) {
  if (v.is_null()) return "";
  switch (s.type) {
    case SettingType::Spec:
    case SettingType::String:
    case SettingType::Enum:
      return v.get<std::string>();
    case SettingType::Int:
      return std::to_string(v.get<long long>());
    case SettingType::Float:
      return numberText(v.get<double>());
    case SettingType::Vec3:
      return numberText(v[0].get<double>()) + "," + numberText(v[1].get<double>()) + "," +
             numberText(v[2].get<double>());
    case SettingType::Flag:
      return v.get<bool>() ? "true" : "false";
    case SettingType::Size:
      return v[0].dump() + "x" + v[1].dump();
    case SettingType::Probe:
      return v["texel"][0].dump() + "," + v["texel"][1].dump() + "," + v["map_size"].dump() + "," +
             v["samples"].dump();
    case SettingType::Animation:
      return v["kind"].get<std::string>() + ":frames=" + v["frames"].dump() +
             ",degrees=" + numberText(v["degrees"].get<double>());
    case SettingType::Lights: {
      std::string t;
      auto vec3 = [](const ojson& x) {
        return numberText(x[0].get<double>()) + "," + numberText(x[1].get<double>()) + "," +
               numberText(x[2].get<double>());
      };
      for (const ojson& l : v) {
        const std::string type = l["type"].get<std::string>();
        t += (t.empty() ? "" : ";") + type + ":" +
             vec3(l[type == "point" ? "position" : "direction"]) + ":" + vec3(l["color"]) + ":" +
             numberText(l["intensity"].get<double>());
      }
      return t;
    }
  }
  return "";
}

std::string noun(const Setting& s) {
  if (s.key == "light") return "light type";
  std::string n = s.key;
  std::replace(n.begin(), n.end(), '_', ' ');
  return n;
}

std::string unknownChoice(const std::string& kind, const std::string& value,
                          const std::vector<std::string>& choices) {
  std::string msg = "unknown " + kind + " '" + value + "'";
  const std::string near = closestName(value, choices);
  if (!near.empty()) msg += " (did you mean '" + near + "'?)";
  return msg + "; expected " + joinOr(choices);
}

// The range and choices of a canonical value.
void checkValue(const Setting& s, const ojson& v) {
  switch (s.type) {
    case SettingType::Enum: {
      const std::string x = v.get<std::string>();
      if (std::find(s.choices.begin(), s.choices.end(), x) == s.choices.end())
        throw Problem{unknownChoice(noun(s), x, s.choices)};
      return;
    }
    case SettingType::Int: {
      const long long n = v.get<long long>();
      const long long lo =
          s.hasMin ? static_cast<long long>(s.min) : std::numeric_limits<int>::min();
      const long long hi =
          s.hasMax ? static_cast<long long>(s.max) : std::numeric_limits<int>::max();
      if (n < lo || n > hi)
        throw Problem{"must be " + std::string(s.hasMin && s.hasMax ? "in " : "") + s.rangeText()};
      return;
    }
    case SettingType::Float: {
      const double d = v.get<double>();
      const bool below = s.hasMin && (s.minOpen ? !(d > s.min) : !(d >= s.min));
      const bool above = s.hasMax && (s.maxOpen ? !(d < s.max) : !(d <= s.max));
      if (!std::isfinite(d)) throw Problem{"not a finite number"};
      if (below || above)
        throw Problem{"must be " + std::string(s.hasMin && s.hasMax ? "in " : "") + s.rangeText()};
      return;
    }
    case SettingType::Vec3:
      if (s.nonZero && v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0) throw Problem{"must be non-zero"};
      return;
    case SettingType::Size:
      for (const ojson& n : v)
        if (n.get<long long>() < 1 || n.get<long long>() > kMaxSize)
          throw Problem{"width and height must be in 1.." + std::to_string(kMaxSize)};
      return;
    case SettingType::Probe: {
      const long long map = v["map_size"].get<long long>();
      const long long samples = v["samples"].get<long long>();
      if (map < 1 || map > kMaxSize)
        throw Problem{"map_size must be in 1.." + std::to_string(kMaxSize)};
      if (samples < 2 || samples > kMaxSamples)
        throw Problem{"samples must be in 2.." + std::to_string(kMaxSamples)};
      const long long x = v["texel"][0].get<long long>(), y = v["texel"][1].get<long long>();
      if (x >= map || y >= map)
        throw Problem{"texel " + std::to_string(x) + "," + std::to_string(y) + " is outside the " +
                      std::to_string(map) + "x" + std::to_string(map) + " map"};
      return;
    }
    case SettingType::Animation: {
      const std::string kind = v["kind"].get<std::string>();
      if (std::find(kAnimationKinds.begin(), kAnimationKinds.end(), kind) == kAnimationKinds.end())
        throw Problem{unknownChoice("animation", kind, kAnimationKinds)};
      const long long frames = v["frames"].get<long long>();
      if (frames < 2 || frames > kMaxFrames)
        throw Problem{"frames must be in 2.." + std::to_string(kMaxFrames)};
      const double degrees = v["degrees"].get<double>();
      if (!(std::fabs(degrees) <= kMaxDegrees)) throw Problem{"degrees must be in [-360, 360]"};
      return;
    }
    case SettingType::Lights: {
      if (v.size() > kMaxExtraLights)
        throw Problem{std::to_string(v.size()) + " lights: at most " +
                      std::to_string(kMaxExtraLights) + " beside the key light"};
      for (const ojson& l : v) {
        const std::string type = l["type"].get<std::string>();
        if (std::find(kLightTypes.begin(), kLightTypes.end(), type) == kLightTypes.end())
          throw Problem{unknownChoice("light type", type, kLightTypes)};
        if (type == "directional") {
          const ojson& d = l.at("direction");
          if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0)
            throw Problem{"a directional light's direction must be non-zero"};
        }
        for (const ojson& c : l["color"])
          if (!(c.get<double>() >= 0)) throw Problem{"a light's colour must be >= 0"};
        if (!(l["intensity"].get<double>() >= 0) || !std::isfinite(l["intensity"].get<double>()))
          throw Problem{"a light's intensity must be >= 0"};
      }
      return;
    }
    case SettingType::Spec:
    case SettingType::String:
    case SettingType::Flag:
      return;
  }
}

// "'text'" for strings, the JSON otherwise: how a suite or manifest value is quoted.
std::string jsonShown(const ojson& v) {
  return v.is_string() ? "'" + v.get<std::string>() + "'" : v.dump();
}

// ------------------------------------------------------------------ the table

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
  plain(add(make("shadow", "--shadow", T::Spec, "none",
                 "shadow technique spec, e.g. shadowmap:size=1024", "shadowmap:size=64",
                 "shadowmapp")),
        &RenderRequest::shadow);
  plain(add(make("oit", "--oit", T::Spec, "none", "transparency technique spec, e.g. peel, abuffer",
                 "wavg", "pel")),
        &RenderRequest::oit);
  plain(add(make("shading", "--shading", T::Spec, "kajiya-kay",
                 "hair shading model spec: kajiya-kay, marschner or sadeghi, with options "
                 "(`strandbench list`)",
                 "marschner:alpha=-5", "marschnr")),
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
    Setting& s = add(make("primitive", "--primitive", T::Enum, "lines",
                          "strands drawn as lines or camera-facing ribbons", "ribbons", "points"));
    s.choices = {"lines", "ribbons"};
    plain(s, &RenderRequest::primitive);
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
                          "device supports; multisampled: --oit none, wsum, wavg, wboit",
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
  plain(add(make("reference", "--reference", T::Flag, "false",
                 "also render the reference (exact shadows and transparency) and report the "
                 "error against it",
                 "true", "maybe")),
        &RenderRequest::reference);
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
                 "identical outputs; false (--no-run-to-run): once",
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
};
static_assert(std::size(kTypeNames) == static_cast<std::size_t>(SettingType::Lights) + 1);
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
  for (const Setting& s : settingsTable()) {
    if (!keys.empty() && std::find(keys.begin(), keys.end(), s.key) == keys.end()) continue;
    Entry e{&s, nullptr, std::make_shared<std::string>(), std::make_shared<bool>(false)};
    if (s.type == SettingType::Flag) {
      e.option = cmd.add_flag(s.flag, *e.flag, s.help);
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
