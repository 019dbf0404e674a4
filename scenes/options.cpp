#include "scenes/options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace sb {

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

}  // namespace sb
