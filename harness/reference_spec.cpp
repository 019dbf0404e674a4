#include "harness/reference_spec.h"

#include <sstream>

#include "base/errors.h"

namespace sb {

namespace {
constexpr int kMaxAaSamples = 8;
constexpr int kMaxPbrSpp = 1 << 16;
}  // namespace

const std::vector<ReferenceKind>& referenceCatalog() {
  using R = ReferenceSpec;
  static const OptionTable<R> kExact({});
  static const OptionTable<R> kAa({opt::integer(&R::samples, "samples", 4, 1, kMaxAaSamples,
                                                "samples per pixel along each axis, 1..8")});
  static const OptionTable<R> kPbr(
      {opt::choice(&R::mode, "mode", "path", {"transmittance", "single", "path"},
                   "transmittance, single or path"),
       opt::integer(&R::spp, "spp", 16, 1, kMaxPbrSpp,
                    "samples per pixel at most, 1..65536 (transmittance: 1 = the pixel centre)"),
       opt::integer(
           &R::bounces, "bounces", 64, 1, 1024,
           "path: scattering events at most, 1..1024 (Russian roulette ends most paths first)"),
       opt::choice(&R::width, "width", "auto", {"auto", "footprint", "world"},
                   "the strands' width: footprint (the raster's: ribbon_width pixels from the eye, "
                   "ribbon_width light texels from each light), world (the file's thickness, else "
                   "thickness=), auto (footprint for transmittance, world for single and path)"),
       opt::number(&R::thickness, "thickness", "0", 0, 1e6,
                   "world width of strands the file gives none (0: one pixel at the scene's "
                   "centre)"),
       opt::number(&R::noise, "noise", "0", 0, 1,
                   "stop once the noise (the RMS over pixels of each pixel's standard error) is "
                   "below this, after at least 8 samples (0: run all spp)"),
       opt::integer(&R::seed, "seed", 1, 0, 2147483647, "the samples' seed, 0..2^31-1")});
  static const std::vector<ReferenceKind> kinds = {
      {"exact",
       "the aliased exact reference: exact shadows and transparency at one sample per pixel "
       "(error.image, error.visibility, error.own)",
       kExact.infos(), &kExact},
      {"aa",
       "the anti-aliased exact reference: the same at samples x samples per pixel and per light "
       "texel, strands drawn with their true width, box-filtered (error.aa)",
       kAa.infos(), &kAa},
      {"pbr",
       "the CPU strand reference over Embree's curves (pbr/, docs/physics-reference.md): "
       "mode=transmittance shades with the scene's model, each light's visibility the exact "
       "transmittance through every strand crossed; mode=single traces the hair BSDF's single "
       "scattering, every fibre crossed attenuating the light by its forward transmittance; "
       "mode=path path-traces the hair BSDF with multiple scattering. Cached by a hash of its "
       "inputs (error.pbr)",
       kPbr.infos(), &kPbr},
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
  // Each kind's table fills its own fields; the others keep their defaults.
  ReferenceSpec r = kind->table->read(spec, "reference '" + spec.name + "'");
  r.name = spec.name;
  return r;
}

}  // namespace sb
