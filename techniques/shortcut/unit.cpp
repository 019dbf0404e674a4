// --oit shortcut: TressFX ShortCut.
#include "render/common/unit.h"

#include "techniques/shortcut/shortcut.h"

namespace sb {
namespace {
struct O {
  int k;
};
const OptionTable<O> kOptions({opt::integer(
    &O::k, "k", 3, 1, ShortCutOit::kMaxK, "nearest fragments blended in order per pixel, 1..16")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "shortcut",
     .family = Family::Transparency,
     .folder = "shortcut",
     .paper = "TressFX ShortCut",
     .help = "TressFX ShortCut: the k nearest depths by atomic min, those fragments blended in "
             "order, the rest as a weighted average under the product of (1 - alpha)",
     .options = kOptions.infos(),
     .caps = {.msaaRefusal = "the k nearest depths of each pixel are atomic mins in per-pixel "
                             "storage buffers: samples would multiply them by N; not supported"},
     .makeOit = [](const OptionReader& r) {
       return std::make_unique<ShortCutOit>(kOptions.read(r).k);
     }});
