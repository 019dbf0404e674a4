#include "base/options.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace sb {

namespace {

std::string trim(const std::string& s) {
  std::size_t a = 0, e = s.size();
  while (a < e && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (e > a && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(a, e - a);
}

}  // namespace

Spec Spec::parse(const std::string& text) {
  Spec spec;
  const std::size_t colon = text.find(':');
  spec.name = trim(text.substr(0, colon));
  if (spec.name.empty()) {
    throw InputError("spec '" + text + "': empty scene name (expected name:key=value,...)");
  }
  if (colon == std::string::npos) return spec;
  const std::string rest = text.substr(colon + 1);
  if (trim(rest).empty()) return spec;  // "name:" is the same as "name"
  std::size_t pos = 0;
  while (pos <= rest.size()) {
    std::size_t comma = rest.find(',', pos);
    if (comma == std::string::npos) comma = rest.size();
    const std::string item = rest.substr(pos, comma - pos);
    pos = comma + 1;
    if (trim(item).empty()) {
      throw InputError("spec '" + text +
                       "': empty option (two commas in a row or a trailing comma)");
    }
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) {
      throw InputError("spec '" + text + "': option '" + trim(item) +
                       "' has no '=' (expected key=value)");
    }
    const std::string key = trim(item.substr(0, eq));
    const std::string value = trim(item.substr(eq + 1));
    if (key.empty()) {
      throw InputError("spec '" + text + "': option '" + trim(item) + "' has an empty key");
    }
    if (!spec.options.emplace(key, value).second) {
      throw InputError("spec '" + text + "': option '" + key + "' is given more than once");
    }
  }
  return spec;
}

std::string Spec::str() const {
  std::string s = name;
  char sep = ':';
  for (const auto& [key, value] : options) {
    s += sep;
    s += key;
    s += '=';
    s += value;
    sep = ',';
  }
  return s;
}

std::string closestName(const std::string& name, const std::vector<std::string>& valid) {
  std::string best;
  std::size_t bestDist = std::string::npos;
  for (const auto& v : valid) {
    std::vector<std::size_t> row(v.size() + 1);
    for (std::size_t j = 0; j <= v.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= name.size(); ++i) {
      std::size_t prev = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= v.size(); ++j) {
        const std::size_t cur = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, prev + (name[i - 1] != v[j - 1] ? 1u : 0u)});
        prev = cur;
      }
    }
    if (row[v.size()] < bestDist) {
      bestDist = row[v.size()];
      best = v;
    }
  }
  // Only suggest names that are plausibly a typo.
  return bestDist <= std::max<std::size_t>(2, name.size() / 3) ? best : "";
}

std::string unknownNameMessage(const std::string& kind, const std::string& name,
                               const std::vector<std::string>& valid) {
  std::string msg = "unknown " + kind + " '" + name + "'";
  const std::string near = closestName(name, valid);
  if (!near.empty()) msg += " (did you mean '" + near + "'?)";
  msg += "; valid " + kind + "s:";
  for (std::size_t i = 0; i < valid.size(); ++i) msg += (i ? ", " : " ") + valid[i];
  return msg;
}

OptionReader::OptionReader(const Spec& spec, const std::vector<OptionInfo>& known, std::string what)
    : spec_(spec), known_(known), what_(std::move(what)) {
  std::vector<std::string> names;
  for (const auto& o : known_) names.push_back(o.name);
  for (const auto& [key, value] : spec_.options) {
    if (std::find(names.begin(), names.end(), key) != names.end()) continue;
    std::string msg = "unknown option '" + key + "' for " + what_;
    const std::string near = closestName(key, names);
    if (!near.empty()) msg += " (did you mean '" + near + "'?)";
    msg += "; valid options:";
    for (const auto& n : names) msg += " " + n;
    if (names.empty()) msg += " none";
    throw InputError(msg);
  }
  for (const auto& o : known_) validate(o);
}

std::string shortestNumber(double v) {
  char buf[32];
  // A float widened (options land in float members): the float's shortest text, "0.002"
  // rather than "0.0020000000949949026"; it reads back as the same float.
  const float f = static_cast<float>(v);
  const auto r = static_cast<double>(f) == v ? std::to_chars(buf, buf + sizeof buf, f)
                                             : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

const char* optionKindName(OptionKind k) {
  switch (k) {
    case OptionKind::Integer:
      return "integer";
    case OptionKind::Number:
      return "number";
    case OptionKind::Choice:
      return "choice";
    case OptionKind::Flag:
      return "flag";
    case OptionKind::Text:
      break;
  }
  return "text";
}

const OptionInfo& OptionReader::declared(const std::string& name) const {
  for (const auto& o : known_)
    if (o.name == name) return o;
  throw InputError("internal: option '" + name + "' not declared for " + what_);
}

void OptionReader::validate(const OptionInfo& o) const {
  switch (o.kind) {
    case OptionKind::Integer:
      integer(o.name);
      break;
    case OptionKind::Number:
      number(o.name);
      break;
    case OptionKind::Choice:
    case OptionKind::Flag:
      choice(o.name);
      break;
    case OptionKind::Text:
      break;
  }
}

double OptionReader::number(const std::string& name) const {
  const OptionInfo& o = declared(name);
  return number(name, o.min, o.max);
}

long long OptionReader::integer(const std::string& name) const {
  const OptionInfo& o = declared(name);
  return integer(name, static_cast<long long>(o.min), static_cast<long long>(o.max));
}

std::string OptionReader::choice(const std::string& name) const {
  const OptionInfo& o = declared(name);
  return choice(name,
                o.kind == OptionKind::Flag ? std::vector<std::string>{"on", "off"} : o.choices);
}

bool OptionReader::flag(const std::string& name) const { return choice(name) == "on"; }

bool OptionReader::has(const std::string& name) const { return spec_.options.count(name) > 0; }

std::string OptionReader::raw(const std::string& name) const {
  auto it = spec_.options.find(name);
  if (it != spec_.options.end()) return it->second;
  return declared(name).defaultValue;
}

std::string OptionReader::text(const std::string& name) const { return raw(name); }

double OptionReader::number(const std::string& name, double min, double max) const {
  const std::string s = raw(name);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
    throw InputError(what_ + ": option " + name + "=" + s + " is not a finite number");
  if (v < min || v > max)
    throw InputError(what_ + ": option " + name + "=" + s + " is out of range [" +
                     std::to_string(min) + ", " + std::to_string(max) + "]");
  return v;
}

long long OptionReader::integer(const std::string& name, long long min, long long max) const {
  const std::string s = raw(name);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
    throw InputError(what_ + ": option " + name + "=" + s + " is not an integer");
  if (v < min || v > max)
    throw InputError(what_ + ": option " + name + "=" + s + " is out of range [" +
                     std::to_string(min) + ", " + std::to_string(max) + "]");
  return v;
}

std::string OptionReader::choice(const std::string& name,
                                 const std::vector<std::string>& valid) const {
  const std::string s = raw(name);
  if (std::find(valid.begin(), valid.end(), s) != valid.end()) return s;
  std::string msg = what_ + ": option " + name + "=" + s + " is not one of";
  for (const auto& v : valid) msg += " " + v;
  const std::string near = closestName(s, valid);
  if (!near.empty()) msg += " (did you mean '" + near + "'?)";
  throw InputError(msg);
}

namespace opt {

OptionInfo integer(std::string name, long long def, long long min, long long max,
                   std::string help) {
  return {std::move(name),
          std::to_string(def),
          std::move(help),
          OptionKind::Integer,
          static_cast<double>(min),
          static_cast<double>(max),
          {}};
}

OptionInfo number(std::string name, std::string def, double min, double max, std::string help) {
  return {std::move(name), std::move(def), std::move(help), OptionKind::Number, min, max, {}};
}

OptionInfo choice(std::string name, std::string def, std::vector<std::string> choices,
                  std::string help) {
  return {std::move(name),   std::move(def), std::move(help), OptionKind::Choice, 0, 0,
          std::move(choices)};
}

OptionInfo flag(std::string name, bool def, std::string help) {
  return {std::move(name), def ? "on" : "off", std::move(help), OptionKind::Flag, 0, 0,
          {"on", "off"}};
}

OptionInfo text(std::string name, std::string def, std::string help) {
  return {std::move(name), std::move(def), std::move(help), OptionKind::Text, 0, 0, {}};
}

}  // namespace opt

}  // namespace sb
