// --shadow msm: moment shadow maps.
#include "render/common/unit.h"

#include "techniques/msm/msm.h"

SB_TECHNIQUE(
    {.name = "msm",
     .family = Family::Shadow,
     .folder = "msm",
     .paper = "Muenstermann et al. 2018; Peters & Klein 2015",
     .help = "moment shadow maps for semi-transparent occluders (Muenstermann et al. 2018's shadow "
             "variant; Peters & Klein 2015): absorbance-weighted moments of light depth, mboit's "
             "reconstruction with the paper's bias",
     .options = {opt::moments(), opt::momentKind(), opt::mapSize(), opt::bias()},
     // In fp32 at dense hair it is not (msm.h).
     .caps = {.monotone = false},
     .makeShadow = [](const OptionReader& o) {
       return std::make_unique<MomentShadowMaps>(MomentShadowMaps::readOptions(o));
     }});
