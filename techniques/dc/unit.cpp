// --shadow dc: density clustering.
#include "render/common/unit.h"

#include "techniques/dc/dc.h"

SB_TECHNIQUE(
    {.name = "dc",
     .family = Family::Shadow,
     .folder = "dc",
     .paper = "Mertens et al. 2004",
     .help = "density clustering (Mertens et al. 2004): per-texel k-means of fragment depths",
     .options = {opt::mapSize(), opt::bias(),
                 opt::integer("clusters", 4, 1, DensityClusteringShadow::kMaxClusters,
                              "depth clusters per texel (one channel each, 4 per layer), 1..8"),
                 opt::integer("iterations", 2, 1, 64,
                              "k-means iterations (passes over the hair), 1..64")},
     .stepped = SteppedOption{"clusters", false, 1, 8},
     .makeShadow = [](const OptionReader& o) {
       return std::make_unique<DensityClusteringShadow>(DensityClusteringShadow::readOptions(o));
     }});
