// Parameters of opacity shadow maps (binding 8), for the map passes and the lookup.
#include "slots.h"
layout(std140, binding = SB_SLOT_OSM_PARAMS) uniform OsmParams {
  mat4 osmViewProj;
  vec4 osmParams;   // bias (light depth units), map size, shadow alpha, weight per fragment
  ivec4 osmLayout;  // tile columns, maps, atlases, filter (opacity_filter.glsl)
  vec4 osmSlices[129];  // D_0..D_n (n <= 512), 4 per vec4
};
#define SB_OSM_SLICE(i) osmSlices[(i) / 4][(i) % 4]
