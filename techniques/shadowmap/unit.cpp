// --shadow shadowmap: the hard shadow map.
#include "render/common/unit.h"

#include "techniques/shadowmap/shadowmap.h"

SB_TECHNIQUE({.name = "shadowmap",
              .family = Family::Shadow,
              .folder = "shadowmap",
              .paper = "Williams 1978",
              .help = "hard shadow map (Williams 1978) cast by the mesh and the hair onto both",
              .options = {opt::mapSize("shadow map resolution (size x size), 1..16384"),
                          opt::bias()},
              .stepped = SteppedOption{"size", true, 16, 4096},
              .makeShadow = [](const OptionReader& o) {
                return std::make_unique<ShadowMap>(static_cast<uint32_t>(o.integer("size")),
                                                   static_cast<float>(o.number("bias")));
              }});
