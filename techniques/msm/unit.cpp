// --shadow msm: moment shadow maps.
#include "render/common/unit.h"

#include "techniques/msm/msm.h"

namespace sb {
namespace {
using O = MomentShadowMaps::Options;
const OptionTable<O> kOptions({opt::moments(&O::moments), opt::momentKind(&O::trig),
                               opt::mapSize(&O::size), opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "msm",
     .family = Family::Shadow,
     .folder = "msm",
     .paper = "Muenstermann et al. 2018; Peters & Klein 2015",
     .help = "moment shadow maps for semi-transparent occluders (Muenstermann et al. 2018's shadow "
             "variant; Peters & Klein 2015): absorbance-weighted moments of light depth, mboit's "
             "reconstruction with the paper's bias",
     .options = kOptions.infos(),
     // In fp32 at dense hair it is not (msm.h).
     .caps = {.monotone = false},
     .makeShadow = build<MomentShadowMaps>(kOptions)});
