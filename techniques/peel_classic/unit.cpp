// --oit peel_classic: depth peeling as the papers time it.
#include "render/common/unit.h"

#include "techniques/peel/peel.h"  // its options, those of depth peeling
#include "techniques/peel_classic/peel_classic.h"

SB_TECHNIQUE({.options = PeelOptions::table().infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<ClassicPeelOit>(PeelOptions::table().read(r).layers);
              }});
