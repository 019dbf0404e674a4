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

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<MomentShadowMaps>(kOptions)});
