// Deep opacity maps lookup: z0 and the layers from the point's texel, the
// opacity interpolated within the point's layer (opacity.glsl), visibility
// (1 - alpha_s)^opacity; 0 behind the opaque mesh.
#include "../common/opaque_shadow.glsl"
#include "dom.glsl"
#include "../common/slots.h"

layout(binding = SB_SLOT_DOM_MAPS) uniform sampler2DArray domMaps;  // the layers, 4 channels each

ivec2 domTexel;

// Channel j of the packed maps: 0 is z0, k = 1..K layer k.
float domChannel(int j) {
  return texelFetch(domMaps, ivec3(domTexel, j / 4), 0)[j % 4];
}

#define SB_DOM_LAYER(k) domChannel(k)
#include "../common/opacity.glsl"

float domZ;  // the point's light depth, less the bias

// The opacity at domZ from texel t's z0 and layers (filters read several).
float domOpacityAt(ivec2 t) {
  domTexel = t;
  return domOpacity(domZ, domChannel(0), domLayout.x);
}
#define SB_FILTER_OPACITY(t) domOpacityAt(t)
#include "../common/opacity_filter.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(domViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, domParams.x) == 0.0) return 0.0;
  domZ = ndc.z - domParams.x;
  float omega = filteredOpacity(uv, int(domParams.y), domLayout.w);
  return opacityVisibility(omega, domParams.z);
}
