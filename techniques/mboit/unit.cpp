// --oit mboit: moment-based OIT.
#include "render/common/unit.h"

#include "techniques/mboit/mboit.h"

namespace sb {
namespace {
using O = MomentOit::Options;
const OptionTable<O> kOptions(
    {opt::moments(&O::moments), opt::momentKind(&O::trig),
     opt::choice(&O::bits, "precision", "32", {{"16", 16}, {"32", 32}},
                 "moment target bits: 16 (RGBA16F, the paper's 16-bit bias) | 32 (RGBA32F)")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = build<MomentOit>(kOptions)});
