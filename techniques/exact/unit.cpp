// --shadow exact: the shadow reference.
#include "render/common/unit.h"

#include "techniques/exact/exact.h"

namespace sb {
namespace {
struct O {
  ExactShadow::Method method;
  uint32_t size;
  float bias;
  uint32_t layers;
};
const OptionTable<O> kOptions(
    {opt::choice(&O::method, "method", "abuffer",
                 {{"peel", ExactShadow::Method::Peel}, {"abuffer", ExactShadow::Method::ABuffer}},
                 "abuffer (sorted light-space fragment lists) | peel (depth peeling "
                 "from the light); the tests prove them identical"),
     opt::mapSize(&O::size, "light map resolution (size x size), 1..16384"), opt::bias(&O::bias),
     opt::layersCap(&O::layers)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "exact",
     .family = Family::Shadow,
     .folder = "exact",
     .paper = "",
     .help = "ground truth: (1-shadow_alpha)^n for the n hair fragments in front, per light texel",
     .options = kOptions.infos(),
     .stepped = SteppedOption{"size", true, 16, 4096},
     .caps = {.exact = true},
     .makeShadow = [](const OptionReader& r) {
       const O o = kOptions.read(r);
       return std::make_unique<ExactShadow>(o.method, o.size, o.bias, o.layers);
     }});
