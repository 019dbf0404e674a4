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

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = build<RayTracedOit>(kOptions)});
