// --oit peel: the transparency reference.
#include "render/common/unit.h"

#include "techniques/peel/peel.h"

SB_TECHNIQUE({.name = "peel",
              .family = Family::Transparency,
              .folder = "peel",
              .paper = "",
              .help = "ground truth: depth peeling from the eye, front to back, every layer",
              .options = {opt::layersCap()},
              .stepped = SteppedOption{"layers", true, 1, 65536},
              .caps = {.exact = true,
                       .msaaRefusal = "peels whole-pixel layers by (depth, primitive) keys kept in "
                                      "per-pixel state buffers: per-sample peeling needs N times "
                                      "that state and a sample-rate pass per layer; not written"},
              .makeOit = [](const OptionReader& o) {
                return std::make_unique<PeelOit>(static_cast<uint32_t>(o.integer("layers")));
              }});
