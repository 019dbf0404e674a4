// Moment shadow maps lookup: the transmittance in front of the point
// reconstructed from its texel's moments (mboit_math.glsl, the paper's bias
// and overestimation); 0 behind the opaque mesh, 1 outside the map.
#include "render/common/opaque_shadow.glsl"
#include "slots.h"
#include "../mboit/mboit_math.glsl"
#include "msm.glsl"

layout(binding = SB_SLOT_MSM_B0) uniform sampler2D msmB0;
layout(binding = SB_SLOT_MSM_LOW) uniform sampler2D msmLow;
#ifdef SB_MSM_HIGH
layout(binding = SB_SLOT_MSM_HIGH) uniform sampler2D msmHigh;
#endif

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(msmViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, msmParams.x) == 0.0) return 0.0;
  int size = int(msmParams.y);
  ivec2 t = min(ivec2(uv * msmParams.y), ivec2(size - 1));
  vec4 high = vec4(0.0);
#ifdef SB_MSM_HIGH
  high = texelFetch(msmHigh, t, 0);
#endif
  return mboitTransmittanceOf(msmN.y, msmN.x, texelFetch(msmB0, t, 0).x, texelFetch(msmLow, t, 0),
                              high, msmDepth(msmLightDepth(worldPos) - msmParams.x), msmParams.w,
                              msmRange.z);
}
