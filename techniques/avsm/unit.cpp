// --shadow avsm: adaptive volumetric shadow maps.
#include "render/common/unit.h"

#include "techniques/avsm/avsm.h"

SB_TECHNIQUE(
    {.name = "avsm",
     .family = Family::Shadow,
     .folder = "avsm",
     .paper = "Salvi et al. 2010",
     .help = "adaptive volumetric shadow maps (Salvi et al. 2010): per texel a curve of at most "
             "`nodes` nodes, each fragment streamed in and the least-area node removed (timing "
             "emulated: resolve in primitive order)",
     .options = {opt::choice("nodes", "8", {"4", "8", "16"},
                             "most nodes per texel curve: 4 | 8 | 16"),
                 opt::mapSize(), opt::bias()},
     .caps = {.interlock = true, .emulatedTiming = true},
     .makeShadow = [](const OptionReader& o) {
       return std::make_unique<AdaptiveVolumetricShadowMaps>(
           AdaptiveVolumetricShadowMaps::readOptions(o));
     }});
