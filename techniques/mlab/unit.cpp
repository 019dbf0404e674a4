// --oit mlab: multi-layer alpha blending.
#include "render/common/unit.h"

#include "techniques/mlab/mlab.h"

namespace sb {
namespace {
struct O {
  int layers;
};
const OptionTable<O> kOptions({opt::integer(&O::layers, "layers", 4, 1, MlabOit::kMaxLayers,
                                            "layers per pixel, 1..32")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "mlab",
     .family = Family::Transparency,
     .folder = "mlab",
     .paper = "Salvi & Vaidyanathan 2014",
     .help = "multi-layer alpha blending (Salvi & Vaidyanathan 2014); without fragment-shader "
             "interlock merged in primitive order in a resolve (timing marked emulated)",
     .options = kOptions.infos(),
     .caps = {.interlock = true,
              .emulatedTiming = true,
              .msaaRefusal =
                  "per-pixel fragment lists (the A-buffer's, merged in primitive order per pixel): "
                  "samples would multiply the lists' memory by N; not supported"},
     .makeOit = [](const OptionReader& r) {
       return std::make_unique<MlabOit>(kOptions.read(r).layers);
     }});
