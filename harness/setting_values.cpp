#include "harness/setting_values.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <sstream>

#include "base/options.h"
#include "harness/json_keys.h"
#include "harness/reference_spec.h"

namespace sb::setting_values {

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

namespace {

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

}  // namespace

ojson vec3Json(const glm::vec3& v) { return ojson::array({double(v.x), double(v.y), double(v.z)}); }
glm::vec3 jsonVec3(const ojson& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

namespace {

constexpr double kMaxDegrees = 360;
const std::vector<std::string> kAnimationKinds = {"light-orbit", "camera-orbit"};
const std::vector<std::string> kLightTypes = {"directional", "point"};

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

}  // namespace

// One extra light, canonical: {"type", "position" or "direction", "color", "intensity"}.
ojson lightJson(const std::string& type, const ojson& at, const ojson& color, double intensity) {
  return {{"type", type},
          {type == "point" ? "position" : "direction", at},
          {"color", color},
          {"intensity", intensity}};
}

namespace {

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

// References: true (the default, exact), false (none), or the list of specs,
// "exact" first, each name once ("exact;aa:samples=4" as text).
ojson referencesFrom(const std::vector<std::string>& specs) {
  ojson list = ojson::array({"exact"});
  std::vector<std::string> names = {"exact"};
  for (const std::string& text : specs) {
    ReferenceSpec r;
    try {
      r = parseReferenceSpec(text.empty() ? "exact" : text);
    } catch (const InputError& e) {
      throw Problem{e.what()};
    }
    if (r.name == defaultReference().name) continue;  // always rendered
    if (std::find(names.begin(), names.end(), r.name) != names.end())
      throw Problem{"two '" + r.name +
                    "' references: give each reference once (its error is error." + r.name + ")"};
    names.push_back(r.name);
    list.push_back(r.str());
  }
  if (list.size() == 1) return true;
  return list;
}

ojson referencesFromText(const std::string& t) {
  if (t == "true" || t.empty()) return true;
  if (t == "false") return false;
  std::vector<std::string> specs;
  std::stringstream in(t);
  for (std::string p; std::getline(in, p, ';');) specs.push_back(p);
  return referencesFrom(specs);
}

}  // namespace

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
    case SettingType::References:
      return referencesFromText(t);
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
    case SettingType::References: {
      if (v.is_boolean()) return v;
      if (v.is_string()) return fromText(s, v.get<std::string>());
      const char* expected =
          "expected true, false, a reference spec (\"NAME:key=value,...\") or a list of them";
      if (!v.is_array() || v.empty()) throw Problem{expected};
      std::vector<std::string> specs;
      for (const ojson& e : v) {
        if (!e.is_string()) throw Problem{expected};
        specs.push_back(e.get<std::string>());
      }
      return referencesFrom(specs);
    }
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
    case SettingType::References: {
      if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
      std::string t;
      for (const ojson& r : v) t += (t.empty() ? "" : ";") + r.get<std::string>();
      return t;
    }
  }
  return "";
}

namespace {

std::string noun(const Setting& s) {
  if (s.key == "light") return "light type";
  std::string n = s.key;
  std::replace(n.begin(), n.end(), '_', ' ');
  return n;
}

}  // namespace

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
    case SettingType::References:
      if (v.is_array()) {
        std::vector<std::string> specs;
        for (const ojson& r : v) specs.push_back(r.get<std::string>());
        referencesFrom(specs);  // names and options in range
      }
      return;
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

}  // namespace sb::setting_values
