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

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = build<StochasticOit>(kOptions)});
