// Parameters of deep opacity maps (binding 8), for the passes and the lookup.
#include "slots.h"
layout(std140, binding = SB_SLOT_DOM_PARAMS) uniform DomParams {
  mat4 domViewProj;
  vec4 domParams;   // bias (light depth units), map size, shadow alpha, depth bits
  ivec4 domLayout;  // layers K, targets, beyond (opacity.glsl kDom*), filter (opacity_filter.glsl)
  vec4 domD[8];     // d_0..d_K (K <= 31), 4 per vec4
};
#define SB_DOM_D(k) domD[(k) / 4][(k) % 4]
