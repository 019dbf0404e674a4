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

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<ClassicPeelOit>(kOptions.read(r).layers);
              }});
