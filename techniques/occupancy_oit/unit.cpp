// --oit occupancy: occupancy-ordered blending.
#include "render/common/unit.h"

#include "techniques/occupancy/occupancy_maps.h"
#include "techniques/occupancy_oit/occupancy_oit.h"

namespace sb {
namespace {
using O = OccupancyOit::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::slices, "slices", 128, 32, OccupancyMaps::kMaxSlices,
                  "occupancy bits per pixel, multiple of 32 (128 per RGBA32UI layer), "
                  "32..1024"),
     opt::integer(&O::slabs, "slabs", 4, 1, OccupancyMaps::kMaxSlabs,
                  "fragment counts per pixel (4 per RGBA32F layer), dividing slices, 1..32"),
     opt::flag(&O::lambda, "lambda", true,
               "on | off: renormalise the hair weights to 1 - prod(1 - alpha) (Lambda "
               "/ hair.a: the printed hair.a / Lambda inverted, see README)"),
     opt::choice(&O::order, "order", "corrected", {{"corrected", 0}, {"paper", 1}, {"printed", 2}},
                 "corrected (the fragment's own share taken out, spread within its "
                 "slice) | paper (the printed F_i / B_total * B_before, not spread) "
                 "| printed (section 3.2 in full: spread within its slice, its own "
                 "share kept; with lambda=on Lambda as printed, hair.a / Lambda)")},
    OccupancyOit::check);
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = build<OccupancyOit>(kOptions)});
