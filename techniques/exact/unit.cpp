// --shadow exact: the shadow reference.
#include "render/common/unit.h"

#include "techniques/exact/exact.h"

namespace sb {
const OptionTable<ExactShadow::Options>& ExactShadow::options() {
  using O = Options;
  static const OptionTable<O> table(
      {opt::choice(&O::method, "method", "abuffer",
                   {{"peel", Method::Peel}, {"abuffer", Method::ABuffer}},
                   "abuffer (sorted light-space fragment lists) | peel (depth peeling "
                   "from the light); the tests prove them identical"),
       opt::mapSize(&O::size, "light map resolution (size x size), 1..16384"), opt::bias(&O::bias),
       opt::layersCap(&O::layers),
       opt::flag(
           &O::jitter, "jitter", false,
           "on | off: lookup jittered by up to half a texel (render/common/light_jitter.glsl): "
           "the reference of a jittered lookup samples as it does"),
       opt::integer(&O::jitterSamples, "jitter_samples", 1, 1, 64,
                    "jitter=on: jittered lookups averaged, 1..64")});
  return table;
}

ExactShadow::Options ExactShadow::optionsOf(const Spec& spec) {
  return options().read(readerFor(findTechnique(Family::Shadow, spec.name), spec));
}
}  // namespace sb

SB_TECHNIQUE({.options = ExactShadow::options().infos(), .makeShadow = [](const OptionReader& r) {
                const ExactShadow::Options o = ExactShadow::options().read(r);
                auto t = std::make_unique<ExactShadow>(o.method, o.size, o.bias, o.layers);
                if (o.jitter) t->jitterLookup(o.jitterSamples);
                return t;
              }});
