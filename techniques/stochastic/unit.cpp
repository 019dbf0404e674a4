// --oit stochastic: stochastic transparency.
#include "render/common/unit.h"

#include "techniques/stochastic/stochastic.h"

namespace sb {
namespace {
using O = StochasticOit::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::samples, "samples", 8, 1, StochasticOit::kMaxSamples,
                  "samples per pixel S, 1..64 (one pass each, S depths per pixel)"),
     opt::integer(&O::seed, "seed", 1, 0, 4294967295LL,
                  "random seed of the coverage masks, 0..4294967295")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "stochastic",
     .family = Family::Transparency,
     .folder = "stochastic",
     .paper = "Enderton et al. 2010",
     .help = "stochastic transparency (Enderton et al. 2010): random sample masks, S sample depths "
             "per pixel, total alpha + depth + accumulate passes, alpha-corrected",
     .options = kOptions.infos(),
     .caps = {.msaaRefusal = "it is sample-based already: its S sample depths per pixel are a "
                             "storage buffer (samples=), since Mesa's CPU drivers rasterize lines "
                             "in a multisampled pass with one depth per pixel"},
     .makeOit = build<StochasticOit>(kOptions)});
