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

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<FourierOpacityMaps>(kOptions)});
