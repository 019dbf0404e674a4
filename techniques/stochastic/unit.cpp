// --oit stochastic: stochastic transparency.
#include "render/common/unit.h"

#include "techniques/stochastic/stochastic.h"

SB_TECHNIQUE(
    {.name = "stochastic",
     .family = Family::Transparency,
     .folder = "stochastic",
     .paper = "Enderton et al. 2010",
     .help = "stochastic transparency (Enderton et al. 2010): random sample masks, S sample depths "
             "per pixel, total alpha + depth + accumulate passes, alpha-corrected",
     .options = {opt::integer("samples", 8, 1, StochasticOit::kMaxSamples,
                              "samples per pixel S, 1..64 (one pass each, S depths per pixel)"),
                 opt::integer("seed", 1, 0, 4294967295LL,
                              "random seed of the coverage masks, 0..4294967295")},
     .caps = {.msaaRefusal = "it is sample-based already: its S sample depths per pixel are a "
                             "storage buffer (samples=), since Mesa's CPU drivers rasterize lines "
                             "in a multisampled pass with one depth per pixel"},
     .makeOit = [](const OptionReader& o) {
       return std::make_unique<StochasticOit>(StochasticOit::readOptions(o));
     }});
