// Williams (1978) hard shadows: a point is lit when its light-space depth is
// not behind the nearest surface the light sees, up to a constant bias.
#include "render/common/light_space.glsl"
#include "slots.h"

layout(binding = SB_SLOT_SHADOWMAP_DEPTH) uniform sampler2D shadowDepth;
#include "uniforms.h"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(shadowViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float occluder = textureLod(shadowDepth, uv, 0.0).r;
  return ndc.z - shadowParams.x > occluder ? 0.0 : 1.0;
}
