// Options as "key=value" pairs of a Spec, declared once and read typed: an
// OptionTable binds each option to a member of a struct (its name, default,
// range or choices and help in one declaration); from the table come the
// descriptor `list` and the docs print (infos()), the checks (unknown names get
// the closest valid name, values are range-checked, InputError: exit status 2)
// and the filled struct (read()). Techniques, shading models, references, scenes
// and run options all declare their options this way; OptionReader is the
// checked string form below it.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "base/errors.h"

namespace sb {

// "name:key=value,key=value" (glmark2 style). Values stay strings until an
// OptionTable (below) reads them into a struct.
struct Spec {
  std::string name;
  std::map<std::string, std::string> options;
  static Spec parse(const std::string& text);  // throws InputError
  std::string str() const;
};

// Description of an option for `strandbench list` and validation. Typed options
// are validated by OptionReader when it is made, so a bad value is refused before
// any work; Text options are read as given.
enum class OptionKind { Text, Integer, Number, Choice, Flag };
struct OptionInfo {
  std::string name;
  std::string defaultValue;
  std::string help;
  OptionKind kind = OptionKind::Text;
  double min = 0, max = 0;           // Integer, Number: the valid range
  std::vector<std::string> choices;  // Choice ("on", "off" for Flag)
};
const char* optionKindName(OptionKind k);  // "text", "integer", "number", "choice", "flag"

// The shortest text that reads back as `v` ("0.002", "1e-06", "16"; a float widened to
// double: the float's shortest, which reads back as that float): how option values are
// written wherever they are read again (OptionTable::given, a child's arguments, messages).
std::string shortestNumber(double v);

// The valid name closest to `name` by edit distance ("" when none is close).
std::string closestName(const std::string& name, const std::vector<std::string>& valid);

// "unknown <kind> '<name>' (did you mean '<closest>'?); valid <kind>s: a, b, c"
std::string unknownNameMessage(const std::string& kind, const std::string& name,
                               const std::vector<std::string>& valid);

class OptionReader {
 public:
  // what: e.g. "scene 'curly'" or "shadow technique 'shadowmap'", used in messages.
  // Throws InputError for an option not in `known`, and for a typed option
  // (given or default) that its declaration refuses.
  OptionReader(const Spec& spec, const std::vector<OptionInfo>& known, std::string what);
  double number(const std::string& name, double min, double max) const;
  long long integer(const std::string& name, long long min, long long max) const;
  std::string choice(const std::string& name, const std::vector<std::string>& valid) const;
  // A typed option, read with its declared range or choices.
  double number(const std::string& name) const;
  long long integer(const std::string& name) const;
  std::string choice(const std::string& name) const;
  bool flag(const std::string& name) const;  // "on" | "off"
  std::string text(const std::string& name) const;
  bool has(const std::string& name) const;  // given explicitly

 private:
  std::string raw(const std::string& name) const;  // given value or the default
  const OptionInfo& declared(const std::string& name) const;
  void validate(const OptionInfo& o) const;
  const Spec& spec_;
  const std::vector<OptionInfo>& known_;
  std::string what_;
};

// Untyped declarations: the descriptor of one option (OptionTable's entries and
// the settings that are not bound to a struct).
namespace opt {
OptionInfo integer(std::string name, long long def, long long min, long long max, std::string help);
OptionInfo number(std::string name, std::string def, double min, double max, std::string help);
OptionInfo choice(std::string name, std::string def, std::vector<std::string> choices,
                  std::string help);
OptionInfo flag(std::string name, bool def, std::string help);  // on | off
OptionInfo text(std::string name, std::string def, std::string help);
}  // namespace opt

// One option bound to a member of S: its descriptor and how its checked value
// lands in the struct.
template <class S>
struct Option {
  OptionInfo info;
  std::function<void(S&, const OptionReader&)> fill;
  std::function<std::string(const S&)> show;  // the member's value as option text
};

namespace opt {
// Declarations (each a group of one or more options) in one list, in order.
template <class S>
std::vector<Option<S>> group(std::initializer_list<std::vector<Option<S>>> groups) {
  std::vector<Option<S>> out;
  for (const auto& g : groups) out.insert(out.end(), g.begin(), g.end());
  return out;
}
}  // namespace opt

// The options of S, each declared once (opt::integer(&S::member, ...) below).
// `finish` runs on the filled struct: rules between options (throw InputError) and
// values derived from several.
template <class S>
class OptionTable {
 public:
  OptionTable(std::initializer_list<std::vector<Option<S>>> groups,
              std::function<void(S&)> finish = {})
      : options_(opt::group<S>(groups)), finish_(std::move(finish)) {}
  std::vector<OptionInfo> infos() const {
    std::vector<OptionInfo> out;
    for (const auto& o : options_) out.push_back(o.info);
    return out;
  }
  // From a reader made with infos() (every value already checked).
  S read(const OptionReader& r) const {
    S s{};
    for (const auto& o : options_) o.fill(s, r);
    if (finish_) finish_(s);
    return s;
  }
  // The options whose value in `s` is not their default, as (name, text): what a child
  // process is given to read the same struct.
  std::vector<std::pair<std::string, std::string>> given(const S& s) const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& o : options_)
      if (const std::string t = o.show(s); t != o.info.defaultValue)
        out.emplace_back(o.info.name, t);
    return out;
  }
  // what: e.g. "reference 'aa'", used in messages.
  S read(const Spec& spec, const std::string& what) const {
    const std::vector<OptionInfo> known = infos();
    return read(OptionReader(spec, known, what));
  }

 private:
  std::vector<Option<S>> options_;
  std::function<void(S&)> finish_;
};

// Typed declarations, bound to a member. They return a one-element group so that
// shared declarations (a list of options) and single ones mix in one table.
namespace opt {
template <class S, class M>
std::vector<Option<S>> integer(M S::*m, std::string name, long long def, long long min,
                               long long max, std::string help) {
  OptionInfo i = integer(name, def, min, max, std::move(help));
  return {{std::move(i),
           [m, name](S& s, const OptionReader& r) { s.*m = static_cast<M>(r.integer(name)); },
           [m](const S& s) { return std::to_string(static_cast<long long>(s.*m)); }}};
}
template <class S, class M>
std::vector<Option<S>> number(M S::*m, std::string name, std::string def, double min, double max,
                              std::string help) {
  OptionInfo i = number(name, std::move(def), min, max, std::move(help));
  return {{std::move(i),
           [m, name](S& s, const OptionReader& r) { s.*m = static_cast<M>(r.number(name)); },
           [m](const S& s) { return shortestNumber(static_cast<double>(s.*m)); }}};
}
// A choice whose names stand for values of the member (an enum, a constant, a count).
template <class S, class M>
std::vector<Option<S>> choice(M S::*m, std::string name, std::string def,
                              std::vector<std::pair<std::string, M>> values, std::string help) {
  std::vector<std::string> names;
  for (const auto& v : values) names.push_back(v.first);
  OptionInfo i = choice(name, std::move(def), std::move(names), std::move(help));
  return {{std::move(i),
           [m, name, values](S& s, const OptionReader& r) {
             const std::string c = r.choice(name);
             for (const auto& v : values)
               if (v.first == c) s.*m = v.second;
           },
           [m, values](const S& s) {
             for (const auto& v : values)
               if (v.second == s.*m) return v.first;
             return std::string();
           }}};
}
// A choice kept as its name.
template <class S>
std::vector<Option<S>> choice(std::string S::*m, std::string name, std::string def,
                              std::vector<std::string> choices, std::string help) {
  OptionInfo i = choice(name, std::move(def), std::move(choices), std::move(help));
  return {{std::move(i), [m, name](S& s, const OptionReader& r) { s.*m = r.choice(name); },
           [m](const S& s) { return s.*m; }}};
}
template <class S>
std::vector<Option<S>> flag(bool S::*m, std::string name, bool def, std::string help) {
  OptionInfo i = flag(name, def, std::move(help));
  return {{std::move(i), [m, name](S& s, const OptionReader& r) { s.*m = r.flag(name); },
           [m](const S& s) { return std::string(s.*m ? "on" : "off"); }}};
}
template <class S>
std::vector<Option<S>> text(std::string S::*m, std::string name, std::string def,
                            std::string help) {
  OptionInfo i = text(name, std::move(def), std::move(help));
  return {{std::move(i), [m, name](S& s, const OptionReader& r) { s.*m = r.text(name); },
           [m](const S& s) { return s.*m; }}};
}
// The options of a part of S (a member struct shared by several tables), as options of S.
template <class S, class P>
std::vector<Option<S>> nested(P S::*part, std::vector<Option<P>> options) {
  std::vector<Option<S>> out;
  for (auto& o : options)
    out.push_back(
        {std::move(o.info),
         [part, fill = std::move(o.fill)](S& s, const OptionReader& r) { fill(s.*part, r); },
         [part, show = std::move(o.show)](const S& s) { return show(s.*part); }});
  return out;
}
// The options of a base of S (declarations shared by several structs derived from P), as
// options of S.
template <class S, class P>
requires std::is_base_of_v<P, S> std::vector<Option<S>> inherited(std::vector<Option<P>> options) {
  std::vector<Option<S>> out;
  for (auto& o : options)
    out.push_back({std::move(o.info),
                   [fill = std::move(o.fill)](S& s, const OptionReader& r) { fill(s, r); },
                   [show = std::move(o.show)](const S& s) { return show(s); }});
  return out;
}
}  // namespace opt

}  // namespace sb
