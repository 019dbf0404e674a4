// --shadow occupancy: occupancy maps from the light.
#include "render/common/unit.h"

#include "techniques/occupancy/occupancy.h"
#include "techniques/occupancy/occupancy_maps.h"

namespace sb {
namespace {
using O = OccupancyShadow::Options;
const OptionTable<O> kOptions(
    {opt::mapSize(&O::size), opt::bias(&O::bias),
     opt::integer(&O::slices, "slices", 128, 32, OccupancyMaps::kMaxSlices,
                  "occupancy bits per texel, multiple of 32 (128 per RGBA32UI layer), "
                  "32..1024"),
     opt::integer(&O::slabs, "slabs", 4, 1, OccupancyMaps::kMaxSlabs,
                  "fragment counts per texel (4 per RGBA32F layer), dividing slices, 1..32"),
     opt::choice(&O::slabMapChoice, "slab_map", "on",
                 {{"on", O::SlabMap::On}, {"off", O::SlabMap::Off}, {"count", O::SlabMap::Count}},
                 "on | off (every set bit counts as one fragment; not the paper's) | "
                 "count (the paper's occupancy-only variant: each set bit counts F/S, F "
                 "the texel's fragment count, S its set bits; one count per texel)"),
     opt::flag(&O::jitter, "jitter", false,
               "on | off: lookup jittered by up to half a texel (anti-aliasing)"),
     opt::integer(&O::jitterSamples, "jitter_samples", 1, 1, 64,
                  "jitter=on: jittered lookups averaged (the paper's use), 1..64")},
    OccupancyShadow::finish);
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<OccupancyShadow>(kOptions)});
