// --oit wsum and --oit wavg: one class, two weightings.
#include "render/common/unit.h"

#include "techniques/weighted/weighted.h"

SB_TECHNIQUE(
    {.name = "wsum",
     .family = Family::Transparency,
     .folder = "weighted",
     .paper = "Meshkin 2007; Bavoil & Myers 2008",
     .help = "weighted sum (Meshkin 2007; Bavoil & Myers 2008): C = sum(a c) + (1 - sum a) C_dst, "
             "saturated to [0,1]",
     .caps = {.multisampling = true},
     .makeOit = [](const OptionReader&) {
       return std::make_unique<WeightedOit>(WeightedOit::Mode::Sum);
     }});
SB_TECHNIQUE(
    {.name = "wavg",
     .family = Family::Transparency,
     .folder = "weighted",
     .paper = "Bavoil & Myers 2008",
     .help =
         "weighted average (Bavoil & Myers 2008): avg colour sum(a c)/sum(a), T = (1 - sum(a)/n)^n",
     .caps = {.multisampling = true},
     .makeOit = [](const OptionReader&) {
       return std::make_unique<WeightedOit>(WeightedOit::Mode::Average);
     }});
