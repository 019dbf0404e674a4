// --shadow shadowmap: the hard shadow map.
#include "render/common/unit.h"

#include "techniques/shadowmap/shadowmap.h"

namespace sb {
namespace {
struct O {
  uint32_t size;
  float bias;
};
const OptionTable<O> kOptions(
    {opt::mapSize(&O::size, "shadow map resolution (size x size), 1..16384"), opt::bias(&O::bias)});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShadow = [](const OptionReader& r) {
                const O o = kOptions.read(r);
                return std::make_unique<ShadowMap>(o.size, o.bias);
              }});
