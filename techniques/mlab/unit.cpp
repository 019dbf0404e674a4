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

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<MlabOit>(kOptions.read(r).layers);
              }});
