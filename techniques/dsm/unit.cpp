// --shadow dsm: deep shadow maps.
#include "render/common/unit.h"

#include "techniques/dsm/dsm.h"

namespace sb {
namespace {
using O = DeepShadowMaps::Options;
const OptionTable<O> kOptions(
    {opt::number(&O::epsilon, "epsilon", "0.01", 0.0, 1.0,
                 "greatest visibility error of the compression (0: exact), 0..1"),
     opt::integer(&O::maxNodes, "max_nodes", 64, 2, 65536,
                  "most nodes kept per texel (more are cut and reported), 2..65536"),
     opt::mapSize(&O::size), opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<DeepShadowMaps>(kOptions)});
