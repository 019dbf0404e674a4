// --shadow avsm: adaptive volumetric shadow maps.
#include "render/common/unit.h"

#include "techniques/avsm/avsm.h"

namespace sb {
namespace {
using O = AdaptiveVolumetricShadowMaps::Options;
const OptionTable<O> kOptions({opt::choice(&O::nodes, "nodes", "8",
                                           {{"4", 4u}, {"8", 8u}, {"16", 16u}},
                                           "most nodes per texel curve: 4 | 8 | 16"),
                               opt::mapSize(&O::size), opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(),
              .makeShadow = build<AdaptiveVolumetricShadowMaps>(kOptions)});
