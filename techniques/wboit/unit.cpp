// --oit wboit: weighted blended OIT.
#include "render/common/unit.h"

#include "techniques/wboit/wboit.h"

SB_TECHNIQUE(
    {.name = "wboit",
     .family = Family::Transparency,
     .folder = "wboit",
     .paper = "McGuire & Bavoil 2013",
     .help = "weighted blended OIT (McGuire & Bavoil 2013): depth-weighted average, exact coverage",
     .options = {opt::choice("weight", "eq10", {"const", "eq7", "eq8", "eq9", "eq10"},
                             "const | eq7 | eq8 | eq9 | eq10: the paper's depth weight w(z, a) "
                             "(eq10: window depth)"),
                 opt::choice("precision", "32", {"16", "32"},
                             "accumulation target bits: 16 (RGBA16F) | 32 (RGBA32F)")},
     .caps = {.multisampling = true},
     .makeOit = [](const OptionReader& o) {
       return std::make_unique<WeightedBlendedOit>(
           WeightedBlendedOit::weightFromName(o.choice("weight")),
           o.choice("precision") == "16" ? 16 : 32);
     }});
