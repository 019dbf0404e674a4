// AVSM lookup: the point's texel curve interpolated at the point's light depth
// (avsm_math.glsl); 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "slots.h"

#include "uniforms.h"
layout(std430, binding = SB_SLOT_AVSM_COUNT) readonly buffer AvsmCount { uint avsmCount[]; };
layout(std430, binding = SB_SLOT_AVSM_NODES) readonly buffer AvsmNodes { vec2 avsmNodes[]; };
// The texel's curve, read in place.
uint avsmBase;
int avsmTexelCount;
#define SB_AVSM_N(i) avsmNodes[avsmBase + uint(i)]
#define SB_AVSM_COUNT avsmTexelCount
#define SB_AVSM_READ_ONLY
#include "avsm_math.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(avsmViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, avsmParams.x) == 0.0) return 0.0;
  uint size = uint(avsmParams.y);
  uvec2 t = min(uvec2(uv * avsmParams.y), uvec2(size - 1u));
  uint texel = t.y * size + t.x;
  avsmBase = texel * uint(SB_AVSM_NODES + 2);
  avsmTexelCount = int(avsmCount[texel]);
  return avsmValue(ndc.z - avsmParams.x, false);
}
