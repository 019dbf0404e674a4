// --shadow voxel: voxelized hair density.
#include "render/common/unit.h"

#include "techniques/voxel/voxel.h"

namespace sb {
namespace {
using O = VoxelDensityShadow::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::grid, "grid", 128, 4, 256,
                  "slices over the hair's depth range, columns per side (<= size), 4..256"),
     opt::integer(&O::steps, "steps", 128, 1, 4096,
                  "march steps over the hair's depth range from the light, 1..4096"),
     opt::number(&O::densityScale, "density_scale", "1", 0.0, 100.0,
                 "scale of the marched hair count (1: w per fragment), 0..100"),
     opt::mapSize(&O::size, "resolution the hair is splatted at (size x size fragments), 1..16384"),
     opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<VoxelDensityShadow>(kOptions)});
