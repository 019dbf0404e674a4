// --oit peel: the transparency reference.
#include "render/common/unit.h"

#include "techniques/peel/peel.h"

namespace sb {
const OptionTable<PeelOptions>& PeelOptions::table() {
  static const OptionTable<PeelOptions> table({opt::layersCap(&PeelOptions::layers)});
  return table;
}
}  // namespace sb

SB_TECHNIQUE({.options = PeelOptions::table().infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<PeelOit>(PeelOptions::table().read(r).layers);
              }});
