// --oit peel: the transparency reference.
#include "render/common/unit.h"

#include "techniques/peel/peel.h"

namespace sb {
namespace {
struct O {
  uint32_t layers;
};
const OptionTable<O> kOptions({opt::layersCap(&O::layers)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<PeelOit>(kOptions.read(r).layers);
              }});
