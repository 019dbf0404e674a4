// --oit peel_classic: depth peeling as the papers time it.
#include "render/common/unit.h"

#include "techniques/peel_classic/peel_classic.h"

namespace sb {
namespace {
struct O {
  uint32_t layers;
};
const OptionTable<O> kOptions({opt::layersCap(&O::layers)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "peel_classic",
     .family = Family::Transparency,
     .folder = "peel_classic",
     .paper = "Everitt 2001",
     .help = "depth peeling as the papers time it (Everitt 2001): one geometry pass per layer, "
             "depth ties lost and counted",
     .options = kOptions.infos(),
     .caps = {.msaaRefusal = "its second depth test samples the last layer's single-sampled R32F "
                             "depth copy per pixel: a multisampled peel needs per-sample copies "
                             "and sample-rate shading; not written"},
     .makeOit = [](const OptionReader& r) {
       return std::make_unique<ClassicPeelOit>(kOptions.read(r).layers);
     }});
