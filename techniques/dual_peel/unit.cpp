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

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<DualPeelOit>(kOptions.read(r).layers);
              }});
