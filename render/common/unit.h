// A technique as a self-describing unit: each folder under techniques/ states
// what is data about it (CLI name, paper, help, capabilities, the viewer's
// stepped option) in its unit.json, embedded by the build, and its typed options
// and factory in its unit.cpp, which registers it (SB_TECHNIQUE, below). Nothing
// central lists techniques: `strandbench list`, option validation, the viewer's
// stepping, suite validation and docs/techniques.md all read this registry.
// One registry for every kind of unit: base/unit_registry.h.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/options.h"
#include "base/unit_registry.h"
#include "render/common/technique.h"
#include "render/shading/shading_model.h"

namespace sb {

enum class Family { Shadow, Transparency, Shading };
const char* familyName(Family f);  // "shadow", "transparency", "shading"
const char* familyFlag(Family f);  // the CLI flag and JSON key: "shadow", "oit", "shading"

// What a technique can do, declared once here (the renderer and the reports ask
// the descriptor, not the class).
struct Capabilities {
  bool multisampling = false;   // renders into multisampled targets (--msaa N > 1)
  bool interlock = false;       // the paper's algorithm needs fragment-shader interlock
  bool emulatedTiming = false;  // part of the timed work emulates that (reported)
  bool monotone = true;         // shadow: visibility never rises away from the light
  bool exact = false;           // a reference: exact up to rounding
  // Transparency without multisampling: why it refuses --msaa N > 1, printed in
  // the refusal (e.g. "per-pixel lists: samples would multiply their memory by
  // N"). Every transparency technique that is not multisampling states one
  // (TechniqueUnits.EveryTransparencyTakesMsaaOrSaysWhyNot).
  std::string msaaRefusal;
  // Why it does not run on the mesh geometry path (render --geometry mesh), where
  // the strands exist only inside the strand draw (Geometry::strandVertexShader):
  // set by the techniques that read the scene's strand buffers otherwise (in
  // compute passes or back on the CPU). Empty: it runs there.
  std::string meshRefusal;
};

// The option the viewer's arrow keys step (x2 and /2 when doubling, else +1 and
// -1), clamped to [min, max]: the option's range, kept interactive.
struct SteppedOption {
  std::string option;
  bool doubling = false;
  long long min = 0, max = 0;
};

// unit.cpp gives `options` and one factory (and `name` where its unit.json names
// several); the registry fills the rest: `folder` from where unit.cpp is, `family`
// from its factory, the others from the folder's unit.json (describeUnit).
struct TechniqueDescriptor {
  std::string name;  // --shadow NAME, --oit NAME, --shading NAME
  Family family = Family::Shadow;
  std::string folder;  // techniques/<folder>/
  std::string paper;   // what it implements ("" for the baselines)
  std::string help;
  std::vector<OptionInfo> options;
  std::optional<SteppedOption> stepped;
  Capabilities caps;
  bool isDefault = false;  // its family's default: the spec when none is given
  // The factory of its family; the reader has validated every typed option.
  std::function<std::unique_ptr<ShadowTechnique>(const OptionReader&)> makeShadow;
  std::function<std::unique_ptr<OitTechnique>(const OptionReader&)> makeOit;
  std::function<ShadingModel(const OptionReader&)> makeShading;
};

// `file`: the registering unit.cpp (__FILE__), whose folder's unit.json describes it.
struct TechniqueRegistrar {
  TechniqueRegistrar(const char* file, TechniqueDescriptor d);
};

// A technique's folder registers it from its unit.cpp, at file scope:
//   SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<DeepOpacityMaps>(kOptions)});
// (a static registrar in namespace sb; one per line, so a file may register two names, each
// with its `.name`).
#define SB_TECHNIQUE(...) SB_REGISTER(TechniqueRegistrar, __VA_ARGS__)

// A family's techniques: "none" first, then by name.
std::vector<const TechniqueDescriptor*> techniques(Family f);
// Their names, in that order, those `keep` accepts (all when null): messages and help
// texts name techniques through the registry, never by a list of their own.
std::vector<std::string> techniqueNames(Family f,
                                        bool (*keep)(const TechniqueDescriptor&) = nullptr);
// Throws InputError naming the closest registered name.
const TechniqueDescriptor& findTechnique(Family f, const std::string& name);
const TechniqueDescriptor* tryFindTechnique(Family f, const std::string& name);
// The family's default (its one descriptor with isDefault): none for shadows and
// transparency, kajiya-kay for shading.
const TechniqueDescriptor& defaultTechnique(Family f);
// The descriptor's reader for a spec: unknown options and bad values throw InputError.
OptionReader readerFor(const TechniqueDescriptor& d, const Spec& spec);

// Fills `d` from `text`, a unit.json (read from `path`: for messages): its name (the one
// entry, or the entry d.name selects), paper, help, capabilities, stepped option and whether
// it is its family's default. Throws std::logic_error naming the file and the key where it
// is malformed (the registrar runs before main: a unit that cannot describe itself stops the
// program).
void describeUnit(TechniqueDescriptor& d, const std::string& path, const std::string& text);

// Checks a spec as the registry builds it (name, options, values, the factory's
// own checks between options), without a device. Throws InputError.
void checkTechniqueSpec(Family f, const std::string& spec);

// The factory of a technique made from its Options struct: `table` read, then T(options).
template <class T, class O>
auto build(const OptionTable<O>& table) {
  return [&table](const OptionReader& r) { return std::make_unique<T>(table.read(r)); };
}

// Option declarations several techniques share, bound to their Options' members
// (base/options.h): types, ranges, defaults and help stated once.
namespace opt {
// The light map every map-based shadow technique takes: size (1..16384) and bias.
template <class S, class M>
std::vector<Option<S>> mapSize(M S::*m,
                               std::string help = "map resolution (size x size), 1..16384") {
  return integer(m, "size", 512, 1, 16384, std::move(help));
}
template <class S, class M>
std::vector<Option<S>> bias(M S::*m) {
  return number(m, "bias", "0.002", 0.0, 1.0, "depth bias in light depth units [0,1], 0..1");
}
// A cap on the layers peeled (peel, dual_peel, peel_classic, exact).
template <class S, class M>
std::vector<Option<S>> layersCap(M S::*m) {
  return integer(m, "layers", 65536, 1, 1000000,
                 "most layers peeled (a cap that is reported), 1..1000000");
}
// The moments of msm and mboit: the count, and whether they are trigonometric.
template <class S, class M>
std::vector<Option<S>> moments(M S::*m) {
  return choice(m, "moments", "6", {{"4", 4}, {"6", 6}, {"8", 8}},
                "real moments beyond b0: 4 | 6 | 8 (kind=trig: 2, 3, 4 complex trigonometric "
                "moments)");
}
template <class S>
std::vector<Option<S>> momentKind(bool S::*trig) {
  return choice(trig, "kind", "power", {{"power", false}, {"trig", true}},
                "power | trig: power moments of depth or trigonometric moments");
}
}  // namespace opt

}  // namespace sb
