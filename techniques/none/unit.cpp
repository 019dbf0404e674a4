// --shadow none: no shadows, the light always visible.
#include "render/common/unit.h"

#include "techniques/none/none.h"

SB_TECHNIQUE({.name = "none",
              .family = Family::Shadow,
              .folder = "none",
              .paper = "",
              .help = "no shadows: Kajiya-Kay shading with the light always visible",
              .isDefault = true,
              .makeShadow = [](const OptionReader&) { return std::make_unique<NoShadow>(); }});
