// Deep opacity maps lookup: z0 (the depth map, quantized to the depth bits)
// and the layers from the point's texel, the
// opacity interpolated within the point's layer (opacity.glsl), visibility
// (1 - alpha_s)^opacity; 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "dom.glsl"
#include "slots.h"

layout(binding = SB_SLOT_DOM_MAPS) uniform sampler2DArray domMaps;  // the layers, 4 channels each
layout(binding = SB_SLOT_DOM_DEPTH) uniform sampler2D domDepth;     // z0: the hair's depth map

ivec2 domTexel;

// Channel j of the packed maps: k = 1..K layer k (0 is unused).
float domChannel(int j) { return texelFetch(domMaps, ivec3(domTexel, j / 4), 0)[j % 4]; }

#define SB_LAYER_MAP(k) domChannel(k)
#include "layers.glsl"

float domZ;  // the point's light depth, less the bias

// The opacity at domZ from texel t's z0 and layers (filters read several).
float domOpacityAt(ivec2 t) {
  domTexel = t;
  float z0 =
      domQuantize(lightDistance(domViewProj, texelFetch(domDepth, t, 0).r), int(domParams.w));
  return domOpacity(domZ, z0, domLayout.x);
}
#define SB_FILTER_OPACITY(t) domOpacityAt(t)
#include "render/common/opacity_filter.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(domViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, domParams.x) == 0.0) return 0.0;
  domZ = lightDistance(domViewProj, ndc.z - domParams.x);  // bias in window depth
  float omega = filteredOpacity(uv, int(domParams.y), domLayout.w);
  return opacityVisibility(omega, domParams.z);
}
