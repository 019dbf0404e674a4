#include "harness/reference_spec.h"

#include <sstream>

#include "base/errors.h"
#include "scenes/options.h"

namespace sb {

namespace {
constexpr int kMaxAaSamples = 8;
constexpr int kMaxPbrSpp = 1 << 16;
}  // namespace

const std::vector<ReferenceKind>& referenceCatalog() {
  static const std::vector<ReferenceKind> kinds = {
      {"exact",
       "the aliased exact reference: exact shadows and transparency at one sample per pixel "
       "(error.image, error.visibility, error.own)",
       {}},
      {"aa",
       "the anti-aliased exact reference: the same at samples x samples per pixel and per light "
       "texel, strands drawn with their true width, box-filtered (error.aa)",
       {{"samples",
         "4",
         "samples per pixel along each axis, 1..8",
         OptionKind::Integer,
         1,
         kMaxAaSamples,
         {}}}},
      {"pbr",
       "the CPU strand reference over Embree's curves (pbr/, docs/physics-reference.md): "
       "mode=transmittance shades with the scene's model, each light's visibility the exact "
       "transmittance through every strand crossed; mode=single traces the hair BSDF's single "
       "scattering, every fibre crossed attenuating the light by its forward transmittance; "
       "mode=path path-traces the hair BSDF with multiple scattering. Cached by a hash of its "
       "inputs (error.pbr)",
       {{"mode",
         "path",
         "transmittance, single or path",
         OptionKind::Choice,
         0,
         0,
         {"transmittance", "single", "path"}},
        {"spp",
         "16",
         "samples per pixel at most, 1..65536 (transmittance: 1 = the pixel centre)",
         OptionKind::Integer,
         1,
         kMaxPbrSpp,
         {}},
        {"bounces",
         "64",
         "path: scattering events at most, 1..1024 (Russian roulette ends most paths first)",
         OptionKind::Integer,
         1,
         1024,
         {}},
        {"width",
         "auto",
         "the strands' width: footprint (the raster's: ribbon_width pixels from the eye, "
         "ribbon_width light texels from each light), world (the file's thickness, else "
         "thickness=), auto (footprint for transmittance, world for single and path)",
         OptionKind::Choice,
         0,
         0,
         {"auto", "footprint", "world"}},
        {"thickness",
         "0",
         "world width of strands the file gives none (0: one pixel at the scene's centre)",
         OptionKind::Number,
         0,
         1e6,
         {}},
        {"noise",
         "0",
         "stop once the noise (the RMS over pixels of each pixel's standard error) is below "
         "this, after at least 8 samples (0: run all spp)",
         OptionKind::Number,
         0,
         1,
         {}},
        {"seed", "1", "the samples' seed, 0..2^31-1", OptionKind::Integer, 0, 2147483647, {}}}},
  };
  return kinds;
}

std::string ReferenceSpec::str() const {
  if (name == "aa") return "aa:samples=" + std::to_string(samples);
  if (name != "pbr") return name;
  std::ostringstream o;
  o.precision(9);
  o << "pbr:mode=" << mode << ",spp=" << spp << ",bounces=" << bounces << ",width=" << width
    << ",thickness=" << thickness << ",noise=" << noise << ",seed=" << seed;
  return o.str();
}

ReferenceSpec parseReferenceSpec(const std::string& text) {
  const Spec spec = Spec::parse(text);
  std::vector<std::string> names;
  const ReferenceKind* kind = nullptr;
  for (const ReferenceKind& k : referenceCatalog()) {
    names.push_back(k.name);
    if (k.name == spec.name) kind = &k;
  }
  if (!kind) throw InputError(unknownNameMessage("reference", spec.name, names));
  const OptionReader o(spec, kind->options, "reference '" + spec.name + "'");
  ReferenceSpec r;
  r.name = spec.name;
  if (r.name == "aa") r.samples = static_cast<int>(o.integer("samples"));
  if (r.name == "pbr") {
    r.mode = o.choice("mode");
    r.spp = static_cast<int>(o.integer("spp"));
    r.bounces = static_cast<int>(o.integer("bounces"));
    r.width = o.choice("width");
    r.thickness = o.number("thickness");
    r.noise = o.number("noise");
    r.seed = static_cast<int>(o.integer("seed"));
  }
  return r;
}

}  // namespace sb
