// The one registry of every kind of unit that varies: shadow and transparency techniques,
// shading models (render/common/unit.h), references (harness/reference_spec.h), measures
// (harness/measures/measure_unit.h) and scene generators (scenes/scene_unit.h). A unit is a
// folder whose unit.cpp registers its descriptor at file scope, through SB_REGISTER (below);
// the descriptor names the unit, the registry fills its folder from where unit.cpp is.
// Nothing central lists units: each kind's catalog, help, docs and validation read its
// registry. The libraries holding units are linked whole (CMakeLists.txt, WHOLE_ARCHIVE) so
// that no registrar is dropped.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.h"
#include "base/options.h"

namespace sb {

// The units of one kind (D: its descriptor, with a `name` and a `folder`), by name. Each
// kind keeps its registry as a function-local static (filled during static initialisation).
template <class D>
class UnitRegistry {
 public:
  // kind: "reference", "measure", ... (messages); root: where its folders are,
  // "harness/references/".
  UnitRegistry(std::string kind, std::string root)
      : kind_(std::move(kind)), root_(std::move(root)) {}

  // The folder of a unit registering from `file` (its unit.cpp's __FILE__, absolute or
  // relative): the one after the last `root`, as "pbr" in ".../harness/references/pbr/unit.cpp".
  std::string folderOf(const std::string& file) const {
    const std::size_t at = file.rfind(root_);
    if (at == std::string::npos)
      throw std::logic_error(file + ": a " + kind_ + " registers from " + root_ +
                             "<folder>/unit.cpp");
    const std::size_t begin = at + root_.size();
    return file.substr(begin, file.find('/', begin) - begin);
  }

  // Adds `d`, its folder filled from `file`. The registrars run before main: a unit without
  // a name or with one already taken stops the program (std::logic_error).
  void add(const char* file, D d) {
    d.folder = folderOf(file);
    if (d.name.empty())
      throw std::logic_error(std::string(file) + ": a " + kind_ + " needs a name");
    const std::string name = d.name;
    if (!units_.emplace(name, std::move(d)).second)
      throw std::logic_error("two " + kind_ + "s named " + name);
  }

  // Every unit, by name.
  std::vector<const D*> all() const {
    std::vector<const D*> out;
    for (const auto& [name, d] : units_) out.push_back(&d);
    return out;
  }
  const D* find(const std::string& name) const {
    const auto it = units_.find(name);
    return it == units_.end() ? nullptr : &it->second;
  }
  // The unit named `name`; else InputError naming the closest registered one.
  const D& get(const std::string& name) const {
    if (const D* d = find(name)) return *d;
    std::vector<std::string> names;
    for (const auto& [n, d] : units_) names.push_back(n);
    throw InputError(unknownNameMessage(kind_, name, names));
  }
  const std::string& kind() const { return kind_; }

 private:
  std::string kind_, root_;
  std::map<std::string, D> units_;
};

// A unit's folder registers it from its unit.cpp, at file scope, with its kind's registrar
// (a type constructible from the file and the descriptor):
//   SB_REGISTER(MeasureRegistrar, {.name = "probe", .help = "...", .measure = ...});
// Each kind names its own shorthand (SB_TECHNIQUE, SB_REFERENCE, SB_MEASURE, SB_SCENE). One
// per line, so that a file may register several units.
#define SB_REGISTER(Registrar, ...)                                              \
  namespace sb {                                                                 \
  namespace {                                                                    \
  const Registrar SB_REGISTER_NAME(registered, __LINE__){__FILE__, __VA_ARGS__}; \
  }                                                                              \
  }
#define SB_REGISTER_NAME(a, b) SB_REGISTER_JOIN(a, b)
#define SB_REGISTER_JOIN(a, b) a##b

}  // namespace sb
