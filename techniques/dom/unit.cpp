// --shadow dom: deep opacity maps.
#include "render/common/unit.h"

#include "render/common/opacity_filter.h"
#include "techniques/dom/dom.h"
#include "techniques/dom/layers.h"

namespace sb {
namespace {
using O = DeepOpacityMaps::Options;
const OptionTable<O> kOptions(
    {opt::integer(&O::layers, "layers", 3, 1, DeepOpacityMaps::kMaxLayers,
                  "opacity layers K, 1..31 (K = 4n-1 fills n RGBA layers of one array)"),
     opt::choice(&O::spacing, "spacing", "linear",
                 {{"constant", glsl::kDomConstant},
                  {"linear", glsl::kDomLinear},
                  {"pow2", glsl::kDomPow2},
                  {"fibonacci", glsl::kDomFibonacci},
                  {"list", DeepOpacityMaps::kSpacingList},
                  {"power", glsl::kDomPower}},
                 "constant | linear | pow2 | fibonacci | list (layer sizes) | power "
                 "(Unreal: K s (k/K)^2.8)"),
     opt::text(&O::listText, "list", "1;2;3",
               "spacing=list: layer sizes as multiples of the layer size, ';'-separated"),
     opt::number(&O::sizeAbs, "size_abs", "0", 0.0, 1.0,
                 "layer size in light depth units (0: use size_frac), 0..1"),
     opt::number(&O::sizeFrac, "size_frac", "0.1", 1e-6, 100.0,
                 "layer size as a fraction of the hair's depth range from the light"),
     opt::choice(
         &O::beyond, "beyond", "last",
         {{"ignore", glsl::kDomIgnore}, {"last", glsl::kDomLast}, {"extend", glsl::kDomExtend}},
         "fragments beyond the last layer: ignore | last | extend"),
     opt::choice(&O::depthBits, "depth_bits", "32", {{"8", 8u}, {"16", 16u}, {"32", 32u}},
                 "precision of z0 (the depth-only pass's 32-bit float depth map), "
                 "quantized where read: 8 | 16 | 32"),
     opt::choice(&O::thesisCounting, "counting", "yuksel", {{"yuksel", false}, {"thesis", true}},
                 "yuksel (a fragment counts in its own layer and every later one, the "
                 "paper) | thesis (its own and every preceding one, Kraft 2018 Listing 3)"),
     opt::opacityFilter(&O::filter), opt::mapSize(&O::size), opt::bias(&O::bias)},
    DeepOpacityMaps::finish);
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = build<DeepOpacityMaps>(kOptions)});
