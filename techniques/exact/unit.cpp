// --shadow exact: the shadow reference.
#include "render/common/unit.h"

#include "techniques/exact/exact.h"

SB_TECHNIQUE(
    {.name = "exact",
     .family = Family::Shadow,
     .folder = "exact",
     .paper = "",
     .help = "ground truth: (1-shadow_alpha)^n for the n hair fragments in front, per light texel",
     .options = {opt::choice("method", "abuffer", {"peel", "abuffer"},
                             "abuffer (sorted light-space fragment lists) | peel (depth peeling "
                             "from the light); the tests prove them identical"),
                 opt::mapSize("light map resolution (size x size), 1..16384"), opt::bias(),
                 opt::layersCap()},
     .stepped = SteppedOption{"size", true, 16, 4096},
     .caps = {.exact = true},
     .makeShadow = [](const OptionReader& o) {
       return std::make_unique<ExactShadow>(
           o.choice("method") == "peel" ? ExactShadow::Method::Peel : ExactShadow::Method::ABuffer,
           static_cast<uint32_t>(o.integer("size")), static_cast<float>(o.number("bias")),
           static_cast<uint32_t>(o.integer("layers")));
     }});
