// --oit rt: ray-traced transparency (software and ray-query tiers).
#include "render/common/unit.h"

#include "techniques/rt_oit/rt_oit.h"

namespace sb {
namespace {
using O = RayTracedOit::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::k, "k", 0, 0, RayTracedOit::kMaxK,
                  "0: every hit in order (a walk per hit); k: one walk keeping the k "
                  "nearest sorted, the rest merged behind them in walk order "
                  "(counted in rt.oit_pixels_merged), 0..32"),
     opt::integer(&O::maxHits, "max_hits", 0, 0, 1000000,
                  "with k=0: hits composited per pixel at most (0: no cap); capped "
                  "pixels are counted and warned about, 0..1000000"),
     opt::nested(&O::walk, rt::tierOptions())},
    RayTracedOit::check);
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "rt",
     .family = Family::Transparency,
     .folder = "rt_oit",
     .paper = "",
     .help = "ray-traced transparency: a primary ray per pixel centre through a BVH of strand "
             "segments (capsule cylinders as wide as the frame draws strands), its hits shaded "
             "with the shadow technique and composited front to back in depth order; software "
             "tier (BVH walked in a compute shader) or ray-query tier (VK_KHR_ray_query over an "
             "acceleration structure of the segments' boxes)",
     .options = kOptions.infos(),
     .caps = {.msaaRefusal = "one primary ray per pixel centre: samples would need a ray "
                             "each; not supported",
              .meshRefusal = "it builds its BVH from the strands read back from the device"},
     .makeOit = build<RayTracedOit>(kOptions)});
