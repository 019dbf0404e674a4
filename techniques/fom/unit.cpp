// --shadow fom: Fourier opacity maps.
#include "render/common/unit.h"

#include "techniques/fom/fom.h"

namespace sb {
namespace {
using O = FourierOpacityMaps::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::coefficients, "coefficients", 8, 1, FourierOpacityMaps::kMaxCoefficients,
                  "frequencies n (2n+1 floats per texel, 4 per RGBA32F layer, 8 layers "
                  "a hair pass), 1..31"),
     opt::mapSize(&O::size), opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "fom",
     .family = Family::Shadow,
     .folder = "fom",
     .paper = "Jansen & Bavoil 2010",
     .help =
         "Fourier opacity maps (Jansen & Bavoil 2010): absorption as a Fourier series in depth, "
         "transmittance clamped to [0,1]",
     .options = kOptions.infos(),
     // Fourier ringing: clamped, not removed.
     .caps = {.monotone = false},
     .makeShadow = build<FourierOpacityMaps>(kOptions)});
