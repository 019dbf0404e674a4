// --shadow osm: opacity shadow maps.
#include "render/common/unit.h"

#include "render/common/opacity_filter.h"
#include "techniques/osm/osm.h"
#include "techniques/osm/slicing.h"

namespace sb {
namespace {
using O = OpacityShadowMaps::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::maps, "maps", 16, 1, 512, "number of opacity maps, 1..512"),
     opt::choice(&O::slicing, "slicing", "uniform",
                 {{"uniform", glsl::kOsmUniform},
                  {"density", glsl::kOsmDensity},
                  {"gamma", glsl::kOsmGamma}},
                 "uniform | density (equal hair points per slice) | gamma (tighter "
                 "near the light)"),
     opt::number(&O::gamma, "gamma", "2", 0.1, 10.0,
                 "slicing=gamma exponent: D_i = near + (far-near)(i/n)^gamma, 0.1..10"),
     opt::choice(&O::multi, "passes", "multi", {{"single", false}, {"multi", true}},
                 "single (one hair pass per map, the original) | multi (up to 6 "
                 "targets x 4 maps a pass)"),
     opt::choice(&O::bits, "bits", "32", {{"8", 8u}, {"16", 16u}, {"32", 32u}},
                 "8 (RGBA8 unorm, kappa-scaled: the paper's limited-bit maps) | 16 "
                 "(RGBA16F: half float counts, not kappa-scaled; exact to 2048 "
                 "fragments) | 32 (RGBA32F)"),
     opt::number(&O::kappa, "kappa", "0", 0.0, 100.0,
                 "bits=8: e^-kappa at opacity 1; 0 derives 8 ln 2 (the paper), 0..100"),
     opt::mapSize(&O::size), opt::bias(&O::bias), opt::opacityFilter(&O::filter)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<OpacityShadowMaps>(kOptions)});
