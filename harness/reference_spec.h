// The references a render is compared with (`--reference [SPEC]`, the suite key
// "reference"): a name and key=value options, parsed as technique specs are
// (Spec::parse, an OptionTable per kind). `exact` is the aliased exact reference (exact
// shadows and transparency at one sample per pixel), the default and always
// rendered when any reference is asked for; `aa:samples=S` the same techniques
// at S x S samples per pixel, box-filtered (harness/render_steps.h,
// renderAaReference); `pbr:mode=transmittance|single|path,...` the CPU strand references
// over Embree (pbr/, harness/pbr_reference.h). A later reference adds itself to
// referenceCatalog().
#pragma once

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sb {

struct ReferenceSpec {
  std::string name = "exact";
  int samples = 1;  // aa: samples per pixel along each axis (S x S per pixel)
  // pbr: the mode (transmittance, single, path), samples per pixel, the path's scattering
  // events at most, the strands' width model (auto: footprint in transmittance mode, world
  // otherwise), the world width of strands without one (0: one pixel at the scene's centre),
  // the noise target (RMS standard error; 0: all spp) and the seed.
  std::string mode = "path";
  int spp = 16, bounces = 64;
  std::string width = "auto";
  double thickness = 0, noise = 0;
  int seed = 1;
  // Canonical text: "exact", "aa:samples=4", "pbr:mode=path,spp=16,bounces=64,...".
  std::string str() const;
  bool operator==(const ReferenceSpec&) const = default;
};

struct ReferenceKind {
  std::string name;
  std::string help;
  std::vector<OptionInfo> options;                    // table->infos()
  const OptionTable<ReferenceSpec>* table = nullptr;  // its options, read into the spec
};

// Every reference, the default (exact) first.
const std::vector<ReferenceKind>& referenceCatalog();

// Throws InputError ("reference 'aa': option samples=9 is out of range [1, 8]")
// for a malformed spec, an unknown name, an unknown option or a value out of range.
ReferenceSpec parseReferenceSpec(const std::string& text);

}  // namespace sb
