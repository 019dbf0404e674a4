// The filter kernels of opacity_filter.glsl (their numbers, compiled as C++)
// and the `filter` option that picks one (dom, osm).
#pragma once

#include <string>
#include <vector>

#include "base/options.h"

namespace sb {
namespace glsl {
#include "render/common/opacity_filter.glsl"
}  // namespace glsl

namespace opt {
// The opacity lookup filter (osm, dom).
template <class S>
std::vector<Option<S>> opacityFilter(int S::*m) {
  return choice(m, "filter", "none",
                {{"none", glsl::kFilterNone},
                 {"pcf2x2", glsl::kFilterPcf2x2},
                 {"pcf6x4", glsl::kFilterPcf6x4},
                 {"pcf6x6", glsl::kFilterPcf6x6},
                 {"box3x3", glsl::kFilterBox3x3}},
                "lookup kernel on the opacity (Unreal): none | pcf2x2 | pcf6x4 (3x3 pcf2x2, 2 "
                "apart) | pcf6x6 (36 texels) | box3x3 (the OSM paper's 3x3 average)");
}
}  // namespace opt

}  // namespace sb
