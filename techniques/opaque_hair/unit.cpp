// --oit none: opaque, depth-tested hair.
#include "render/common/unit.h"

#include "techniques/opaque_hair/opaque_hair.h"

SB_TECHNIQUE({.name = "none",
              .family = Family::Transparency,
              .folder = "opaque_hair",
              .paper = "",
              .help = "no transparency: opaque, depth-tested hair",
              // --msaa: geometry only, no per-pixel data.
              .caps = {.multisampling = true},
              .isDefault = true,
              .makeOit = [](const OptionReader&) { return std::make_unique<OpaqueHair>(); }});
