// --oit none: opaque, depth-tested hair.
#include "render/common/unit.h"

#include "techniques/opaque_hair/opaque_hair.h"

SB_TECHNIQUE({.makeOit = [](const OptionReader&) { return std::make_unique<OpaqueHair>(); }});
