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

SB_TECHNIQUE(
    {.name = "rt",
     .family = Family::Shadow,
     .folder = "rt",
     .paper = "",
     .help = "ray-traced shadows: rays from the point to the light through a BVH of strand "
             "segments (capsule cylinders as wide as the light map draws them), "
             "(1-shadow_alpha) per strand crossed; software tier (BVH walked in the shader) or "
             "ray-query tier (VK_KHR_ray_query over an acceleration structure of the segments' "
             "boxes)",
     .options = kOptions.infos(),
     .stepped = SteppedOption{"rays", true, 1, 256},
     .caps = {.meshRefusal = "it builds its BVH from the strands read back from the device"},
     .makeShadow = build<RayTracedShadow>(kOptions)});
