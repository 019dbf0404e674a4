// --oit peel: the transparency reference.
#include "techniques/common/unit.h"

#include "techniques/peel/peel.h"

SB_TECHNIQUE({.name = "peel",
              .family = Family::Transparency,
              .folder = "peel",
              .paper = "",
              .help = "ground truth: depth peeling from the eye, front to back, every layer",
              .options = {opt::layersCap()},
              .stepped = SteppedOption{"layers", true, 1, 65536},
              .caps = {.exact = true},
              .makeOit = [](const OptionReader& o) {
                return std::make_unique<PeelOit>(static_cast<uint32_t>(o.integer("layers")));
              }});
