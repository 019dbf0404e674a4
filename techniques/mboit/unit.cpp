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

SB_TECHNIQUE(
    {.name = "mboit",
     .family = Family::Transparency,
     .folder = "mboit",
     .paper = "Muenstermann et al. 2018",
     .help = "moment-based OIT (Muenstermann et al. 2018): transmittance from power or "
             "trigonometric moments of log depth, the paper's bias; two hair passes",
     .options = kOptions.infos(),
     .caps =
         {.msaaRefusal =
              "its second pass reads the first pass's moments per pixel (sampler2D): multisampled "
              "moments need per-sample reads of a multisampled target; not written"},
     .makeOit = build<MomentOit>(kOptions)});
