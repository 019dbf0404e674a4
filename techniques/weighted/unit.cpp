// --oit wsum and --oit wavg: one class, two weightings.
#include "render/common/unit.h"

#include "techniques/weighted/weighted.h"

SB_TECHNIQUE({.name = "wsum", .makeOit = [](const OptionReader&) {
                return std::make_unique<WeightedOit>(WeightedOit::Mode::Sum);
              }});
SB_TECHNIQUE({.name = "wavg", .makeOit = [](const OptionReader&) {
                return std::make_unique<WeightedOit>(WeightedOit::Mode::Average);
              }});
