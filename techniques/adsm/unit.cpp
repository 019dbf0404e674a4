// --shadow adsm: approximated deep shadows (TressFX).
#include "render/common/unit.h"

#include "techniques/adsm/adsm.h"

namespace sb {
namespace {
using O = ApproximatedDeepShadows::Options;
const OptionTable<O> kOptions(
    {opt::number(&O::spacing, "spacing", "4", 1e-3, 1e6,
                 "fiber spacing in fiber radii (radius: half the mean strand thickness)"),
     opt::integer(&O::kernel, "kernel", 5, 1, 9,
                  "PCF taps per side, Gaussian weights sigma = kernel/2/2.4 (TressFX), 1..9"),
     opt::mapSize(&O::size), opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.name = "adsm",
              .family = Family::Shadow,
              .folder = "adsm",
              .paper = "TressFX (Tomb Raider 2013)",
              .help = "approximated deep shadows (TressFX, Tomb Raider 2013): one front-depth map, "
                      "(1-alpha)^(dz/(spacing x radius) + 1), Gaussian PCF",
              .options = kOptions.infos(),
              .caps = {.meshRefusal = "it reads the strands' thickness back from the device"},
              .makeShadow = build<ApproximatedDeepShadows>(kOptions)});
