// --shadow none: no shadows, the light always visible.
#include "render/common/unit.h"

#include "techniques/none/none.h"

SB_TECHNIQUE({.makeShadow = [](const OptionReader&) { return std::make_unique<NoShadow>(); }});
