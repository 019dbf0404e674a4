// --oit shortcut: TressFX ShortCut.
#include "render/common/unit.h"

#include "techniques/shortcut/shortcut.h"

SB_TECHNIQUE(
    {.name = "shortcut",
     .family = Family::Transparency,
     .folder = "shortcut",
     .paper = "TressFX ShortCut",
     .help = "TressFX ShortCut: the k nearest depths by atomic min, those fragments blended in "
             "order, the rest as a weighted average under the product of (1 - alpha)",
     .options = {opt::integer("k", 3, 1, ShortCutOit::kMaxK,
                              "nearest fragments blended in order per pixel, 1..16")},
     .caps = {.msaaRefusal = "the k nearest depths of each pixel are atomic mins in per-pixel "
                             "storage buffers: samples would multiply them by N; not supported"},
     .makeOit = [](const OptionReader& o) {
       return std::make_unique<ShortCutOit>(static_cast<int>(o.integer("k")));
     }});
