// --shadow rt: ray-traced strand shadows (software and ray-query tiers).
#include "render/common/unit.h"

#include "techniques/rt/rt.h"

namespace sb {
namespace {
using O = RayTracedShadow::Options;
const OptionTable<O> kOptions(
    {opt::mapSize(&O::size,
                  "the light texel the strand width and the rays' jitter are "
                  "measured in (and the opaque mesh's map), 1..16384"),
     opt::bias(&O::bias),
     opt::integer(&O::rays, "rays", 1, 1, 256,
                  "rays per point, jittered over the light texel at the point "
                  "(1: the point itself), 1..256"),
     opt::integer(&O::maxHits, "max_hits", 0, 0, 1000000,
                  "stop a ray after this many strands (0: no cap); counted in "
                  "rt.max_hits_reached, 0..1000000"),
     opt::nested(&O::walk, rt::tierOptions())});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<RayTracedShadow>(kOptions)});
