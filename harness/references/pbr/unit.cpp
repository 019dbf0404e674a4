// --reference pbr:...: the CPU strand references over Embree (pbr/, pbr_reference.h), their
// options declared once here.
#include "harness/reference_spec.h"
#include "harness/references/pbr/pbr_reference.h"

namespace sb {
namespace {
constexpr int kMaxPbrSpp = 1 << 16;

using R = PbrReference;
const OptionTable<R> kOptions(
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
}  // namespace
}  // namespace sb

SB_REFERENCE(
    {.name = "pbr",
     .help = "the CPU strand reference over Embree's curves (pbr/, docs/physics-reference.md): "
             "mode=transmittance shades with the scene's model, each light's visibility the exact "
             "transmittance through every strand crossed; mode=single traces the hair BSDF's "
             "single scattering, every fibre crossed attenuating the light by its forward "
             "transmittance; mode=path path-traces the hair BSDF with multiple scattering. Cached "
             "by a hash of its inputs (error.pbr)",
     .options = kOptions.infos(),
     .make = [](const OptionReader& reader) {
       return std::make_shared<const R>(kOptions.read(reader));
     }});
