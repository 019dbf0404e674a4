// --shadow dc: density clustering.
#include "render/common/unit.h"

#include "techniques/dc/dc.h"

namespace sb {
namespace {
using O = DensityClusteringShadow::Options;
const OptionTable<O> kOptions(
    {opt::mapSize(&O::size), opt::bias(&O::bias),
     opt::integer(&O::clusters, "clusters", 4, 1, DensityClusteringShadow::kMaxClusters,
                  "depth clusters per texel (one channel each, 4 per layer), 1..8"),
     opt::integer(&O::iterations, "iterations", 2, 1, 64,
                  "k-means iterations (passes over the hair), 1..64")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<DensityClusteringShadow>(kOptions)});
