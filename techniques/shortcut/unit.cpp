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

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                return std::make_unique<ShortCutOit>(kOptions.read(r).k);
              }});
