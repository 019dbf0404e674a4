// AVSM lookup: the point's texel curve interpolated at the point's light depth
// (avsm_math.glsl); 0 behind the opaque mesh.
#include "../common/opaque_shadow.glsl"
#include "../common/slots.h"
#define SB_AVSM_CAP SB_AVSM_NODES
#include "avsm_math.glsl"

layout(std140, binding = SB_SLOT_AVSM_PARAMS) uniform AvsmLookupParams {
  mat4 avsmViewProj;
  vec4 avsmParams;  // x: bias (light depth units), y: map size, z: shadow alpha
};
layout(std430, binding = SB_SLOT_AVSM_COUNT) readonly buffer AvsmCount { uint avsmCount[]; };
layout(std430, binding = SB_SLOT_AVSM_NODES) readonly buffer AvsmNodes { vec2 avsmNodes[]; };

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(avsmViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, avsmParams.x) == 0.0) return 0.0;
  uint size = uint(avsmParams.y);
  uvec2 t = min(uvec2(uv * avsmParams.y), uvec2(size - 1u));
  uint texel = t.y * size + t.x;
  AvsmCurve c;
  c.count = int(avsmCount[texel]);
  for (int k = 0; k < c.count; ++k) c.n[k] = avsmNodes[texel * uint(SB_AVSM_NODES) + uint(k)];
  return avsmValue(c, ndc.z - avsmParams.x, false);
}
