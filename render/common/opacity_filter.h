// The filter kernels of opacity_filter.glsl (their numbers, compiled as C++)
// and the `filter` option that picks one (dom, osm).
#pragma once

#include <string>

#include "scenes/options.h"

namespace sb {
namespace glsl {
#include "render/common/opacity_filter.glsl"
}  // namespace glsl

inline int readFilter(const OptionReader& o) {
  const std::string f = o.choice("filter");
  return f == "pcf2x2"   ? glsl::kFilterPcf2x2
         : f == "pcf6x4" ? glsl::kFilterPcf6x4
         : f == "pcf6x6" ? glsl::kFilterPcf6x6
         : f == "box3x3" ? glsl::kFilterBox3x3
                         : glsl::kFilterNone;
}

}  // namespace sb
