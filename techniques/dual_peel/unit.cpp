// --oit dual_peel: dual depth peeling.
#include "render/common/unit.h"

#include "techniques/dual_peel/dual_peel.h"
#include "techniques/peel/peel.h"  // its options, those of depth peeling

SB_TECHNIQUE({.options = PeelOptions::table().infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<DualPeelOit>(PeelOptions::table().read(r).layers);
              }});
