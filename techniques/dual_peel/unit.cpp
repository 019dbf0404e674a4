// --oit dual_peel: dual depth peeling.
#include "render/common/unit.h"

#include "techniques/dual_peel/dual_peel.h"

namespace sb {
namespace {
struct O {
  uint32_t layers;
};
const OptionTable<O> kOptions({opt::layersCap(&O::layers)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "dual_peel",
     .family = Family::Transparency,
     .folder = "dual_peel",
     .paper = "Bavoil & Myers 2008",
     .help = "dual depth peeling (Bavoil & Myers 2008): the nearest and farthest layers per pass, "
             "ceil(layers/2) peel passes after one min/max depth pass",
     .options = kOptions.infos(),
     .caps = {.msaaRefusal = "its min/max depth and front/back accumulation targets are per-pixel, "
                             "MAX-blended and sampled per pixel by the next pass: per-sample ones "
                             "need sample-rate shading; not written"},
     .makeOit = [](const OptionReader& r) {
       return std::make_unique<DualPeelOit>(kOptions.read(r).layers);
     }});
