// Deep opacity maps lookup: z0 and the layers from the point's texel, the
// opacity interpolated within the point's layer (opacity.glsl), visibility
// (1 - alpha_s)^opacity; 0 behind the opaque mesh.
#include "../common/opaque_shadow.glsl"
#include "dom.glsl"

layout(binding = 9) uniform sampler2D domMap0;
#if SB_DOM_TARGETS > 1
layout(binding = 10) uniform sampler2D domMap1;
#endif
#if SB_DOM_TARGETS > 2
layout(binding = 11) uniform sampler2D domMap2;
#endif
#if SB_DOM_TARGETS > 3
layout(binding = 12) uniform sampler2D domMap3;
#endif
#if SB_DOM_TARGETS > 4
layout(binding = 13) uniform sampler2D domMap4;
#endif
#if SB_DOM_TARGETS > 5
layout(binding = 14) uniform sampler2D domMap5;
#endif

ivec2 domTexel;

// Channel j of the packed maps: 0 is z0, k = 1..K layer k.
float domChannel(int j) {
  int t = j / 4;
  vec4 v = texelFetch(domMap0, domTexel, 0);
#if SB_DOM_TARGETS > 1
  if (t == 1) v = texelFetch(domMap1, domTexel, 0);
#endif
#if SB_DOM_TARGETS > 2
  if (t == 2) v = texelFetch(domMap2, domTexel, 0);
#endif
#if SB_DOM_TARGETS > 3
  if (t == 3) v = texelFetch(domMap3, domTexel, 0);
#endif
#if SB_DOM_TARGETS > 4
  if (t == 4) v = texelFetch(domMap4, domTexel, 0);
#endif
#if SB_DOM_TARGETS > 5
  if (t == 5) v = texelFetch(domMap5, domTexel, 0);
#endif
  return v[j % 4];
}

#define SB_DOM_LAYER(k) domChannel(k)
#include "../common/opacity.glsl"

float shadowVisibility(vec3 worldPos) {
  vec4 clip = domViewProj * vec4(worldPos, 1.0);
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  if (opaqueVisibility(ndc, domParams.x) == 0.0) return 0.0;
  int size = int(domParams.y);
  domTexel = min(ivec2(uv * domParams.y), ivec2(size - 1));
  float omega = domOpacity(ndc.z - domParams.x, domChannel(0), domLayout.x);
  return opacityVisibility(omega, domParams.z);
}
