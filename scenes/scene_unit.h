// A scene generator as a unit: a folder scenes/generators/<name>/ whose unit.cpp declares its
// options bound to its own struct and registers how it makes a scene (SB_SCENE, below), as
// techniques, references and measures register themselves (base/unit_registry.h). Nothing
// central lists scenes: makeScene, sceneCatalog (`strandbench list`, the docs, the settings'
// help) read this registry. The options every scene has (a uniform scale, doubled points,
// the groom) are SceneBase's; makeScene applies them after the unit made its strands.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/options.h"
#include "base/unit_registry.h"
#include "scenes/scene.h"

namespace sb {

// What every scene reads besides its own options: its name (for messages), the seed and the
// stiff cases and groom options makeScene applies to every scene.
struct SceneBase {
  std::string scene;
  uint32_t seed = 1;
  float alpha = 1, shadowAlpha = 0.5f;  // the Scene's hairAlpha and shadowAlpha
  std::string mesh;                     // the opaque mesh's file; "": the unit's own or none
  float scale = 1;
  bool zeroSegments = false;
  // The groom (scenes/groom.h, docs/geometry.md): guides, the generation rule, a crowd.
  uint32_t guides = 0, instances = 1;
  float guideSpread = 0.5f, guideOffset = 0.5f, noise = 0.1f, clump = 0, lod = 1, lodPixels = 0;
  InputError error(const std::string& what) const {
    return InputError("scene '" + scene + "': " + what);
  }
};

// Refused while the options are read, before the scene is named: makeScene prefixes it.
struct UnnamedSceneError : InputError {
  using InputError::InputError;
};

// The limits every generator keeps (strands x points, strands, points per strand).
inline constexpr uint64_t kMaxTotalPoints = 200'000'000;
inline constexpr int64_t kMaxStrands = 50'000'000;
inline constexpr int64_t kMaxPointsPerStrand = 100'000;
// Refuses strands x points over kMaxTotalPoints, naming the scene.
void checkTotal(const SceneBase& o, uint64_t strands, uint64_t points);
// Room for `strands` strands of `points` points in every per-strand and per-point array.
void reserve(Strands& s, std::size_t strands, std::size_t points);

// unit.cpp gives name, help, order and make (sceneUnit builds the last two from its typed
// options); the registry fills `folder`.
struct SceneDescriptor {
  std::string name;  // the spec's name: "curly:strands=..."
  std::string help;
  // `strandbench list` and the docs order scenes by it, then by name.
  int order = 0;
  std::vector<OptionInfo> options;  // the unit's own, then SceneBase's
  // From a reader made with `options` (every value already checked): the scene as the unit
  // makes it, and the options every scene shares, read into `base`.
  std::function<Scene(const OptionReader&, SceneBase& base)> make;
  std::string folder;  // scenes/generators/<folder>/
};

struct SceneRegistrar {
  SceneRegistrar(const char* file, SceneDescriptor d);
};

// A scene generator's folder registers it from its unit.cpp, at file scope:
//   SB_SCENE(sceneUnit<StrayOptions>("stray", "...", 5, {...its options...}, makeStray));
#define SB_SCENE(...) SB_REGISTER(SceneRegistrar, __VA_ARGS__)

// SceneBase's options (scale, zero_segments, the groom's), which every scene takes.
std::vector<Option<SceneBase>> sceneBaseOptions();
// The declarations several units share: alpha= and shadow_alpha=; seed= with its help.
std::vector<Option<SceneBase>> alphaOptions();
std::vector<Option<SceneBase>> seedOption(std::string help);

// Declarations of the scenes' own kinds, bound to a member of S.
namespace scene_opt {
// A number in (0, max]: a range with an open end, refused as "must be greater than 0".
template <class S>
std::vector<Option<S>> positive(float S::*m, std::string name, std::string def, double max,
                                std::string help) {
  OptionInfo info = opt::number(name, std::move(def), 0.0, max, std::move(help));
  return {{std::move(info),
           [m, name](S& s, const OptionReader& r) {
             const double v = r.number(name);
             if (!(v > 0.0))
               throw UnnamedSceneError("option " + name + "=" + r.text(name) +
                                       " is out of range: must be greater than 0");
             s.*m = float(v);
           },
           [m](const S& s) { return shortestNumber(s.*m); }}};
}
// A 0/1 switch (head, zero_segments).
template <class S>
std::vector<Option<S>> zeroOne(bool S::*m, std::string name, bool def, std::string help) {
  OptionInfo info = opt::integer(name, def ? 1 : 0, 0, 1, std::move(help));
  return {{std::move(info), [m, name](S& s, const OptionReader& r) { s.*m = r.integer(name) == 1; },
           [m](const S& s) { return std::string(s.*m ? "1" : "0"); }}};
}
// An option that may be absent (its default empty): read, with its range, only when given.
template <class S>
std::vector<Option<S>> optional(std::string name, std::string help,
                                std::function<void(S&, const OptionReader&)> fill,
                                std::function<std::string(const S&)> show) {
  return {{opt::text(std::move(name), "", std::move(help)), std::move(fill), std::move(show)}};
}
}  // namespace scene_opt

// The descriptor of a scene made by `make` from O (a struct derived from SceneBase), whose
// options are `own` followed by SceneBase's.
template <class O>
requires std::is_base_of_v<SceneBase, O> SceneDescriptor
sceneUnit(std::string name, std::string help, int order,
          std::initializer_list<std::vector<Option<O>>> own, std::function<Scene(const O&)> make) {
  const auto table = std::make_shared<const OptionTable<O>>(
      OptionTable<O>({opt::group<O>(own), opt::inherited<O>(sceneBaseOptions())}));
  return {std::move(name), std::move(help), order, table->infos(),
          [table, make = std::move(make)](const OptionReader& r, SceneBase& base) {
            O o = table->read(r);
            o.scene = base.scene;
            base = o;
            return make(o);
          }};
}

}  // namespace sb
