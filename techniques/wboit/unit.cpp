// --oit wboit: weighted blended OIT.
#include "render/common/unit.h"

#include "techniques/wboit/wboit.h"

namespace sb {
namespace {
struct O {
  int weight;
  int precision;
};
const OptionTable<O> kOptions(
    {opt::choice(&O::weight, "weight", "eq10",
                 {{"const", 0}, {"eq7", 7}, {"eq8", 8}, {"eq9", 9}, {"eq10", 10}},
                 "const | eq7 | eq8 | eq9 | eq10: the paper's depth weight w(z, a) "
                 "(eq10: window depth)"),
     opt::choice(&O::precision, "precision", "32", {{"16", 16}, {"32", 32}},
                 "accumulation target bits: 16 (RGBA16F) | 32 (RGBA32F)")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeOit = [](const OptionReader& r) {
                const O o = kOptions.read(r);
                return std::make_unique<WeightedBlendedOit>(o.weight, o.precision);
              }});
