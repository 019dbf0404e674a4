// A technique as a self-describing unit: each folder under techniques/ declares
// its descriptor (CLI name, family, paper, typed options, capabilities, factory)
// in its own unit.cpp and registers it there (SB_TECHNIQUE, below). Nothing
// central lists techniques: `strandbench list`, option validation, the viewer's
// stepping, suite validation and docs/techniques.md all read this registry.
// sb_techniques is linked whole (CMakeLists.txt) so that no registrar is dropped.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scenes/options.h"
#include "techniques/common/shading_model.h"
#include "techniques/common/technique.h"

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
};

// The option the viewer's arrow keys step (x2 and /2 when doubling, else +1 and
// -1), clamped to [min, max]: the option's range, kept interactive.
struct SteppedOption {
  std::string option;
  bool doubling = false;
  long long min = 0, max = 0;
};

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

struct TechniqueRegistrar {
  explicit TechniqueRegistrar(TechniqueDescriptor d);
};

// A technique's folder registers it from its unit.cpp, at file scope:
//   SB_TECHNIQUE({.name = "dom", .family = Family::Shadow, ...});
// (a static registrar in namespace sb; one per line, so a file may register two names).
#define SB_TECHNIQUE(...)                                                        \
  namespace sb {                                                                 \
  namespace {                                                                    \
  const TechniqueRegistrar SB_TECHNIQUE_NAME(registered, __LINE__){__VA_ARGS__}; \
  }                                                                              \
  }
#define SB_TECHNIQUE_NAME(a, b) SB_TECHNIQUE_JOIN(a, b)
#define SB_TECHNIQUE_JOIN(a, b) a##b

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

// Checks a spec as the registry builds it (name, options, values, the factory's
// own checks between options), without a device. Throws InputError.
void checkTechniqueSpec(Family f, const std::string& spec);

// Option declarations, so that descriptors state types and ranges once.
namespace opt {
OptionInfo integer(std::string name, long long def, long long min, long long max, std::string help);
OptionInfo number(std::string name, std::string def, double min, double max, std::string help);
OptionInfo choice(std::string name, std::string def, std::vector<std::string> choices,
                  std::string help);
OptionInfo flag(std::string name, bool def, std::string help);  // on | off
OptionInfo text(std::string name, std::string def, std::string help);
// The light map every map-based shadow technique takes: size (1..16384) and bias.
OptionInfo mapSize(std::string help = "map resolution (size x size), 1..16384");
OptionInfo bias();
// A cap on the layers peeled (peel, dual_peel, peel_classic, exact).
OptionInfo layersCap();
// The opacity lookup filter (osm, dom).
OptionInfo opacityFilter();
// The moments of msm and mboit.
OptionInfo moments();
OptionInfo momentKind();
// The lobe options ShadingLobes::read reads (the lobe models): diffuse, specular,
// alpha and beta, the models' own options after them.
std::vector<OptionInfo> lobes(std::string diffuseHelp, std::string specularHelp,
                              std::vector<OptionInfo> more, std::string specularDefault = "0.5");
}  // namespace opt

}  // namespace sb
