// Opacity shadow maps lookup: the point's opacity interpolated between the
// two maps enclosing its light depth (opacity.glsl), visibility
// (1 - alpha_s)^(opacity / weight); 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "osm.glsl"
#include "slots.h"

layout(binding = SB_SLOT_OSM_ATLASES) uniform sampler2DArray osmAtlases;  // one atlas per layer

ivec2 osmTexel;  // the point's texel within a tile

// Stored map m (= map m + 1): texel group m / 4 is tile g / atlases of atlas g % atlases.
float osmStored(int m) {
  int g = m / 4;
  int a = g % osmLayout.z;
  int t = g / osmLayout.z;
  ivec2 p = osmTexel + ivec2(t % osmLayout.x, t / osmLayout.x) * int(osmParams.y);
  return texelFetch(osmAtlases, ivec3(p, a), 0)[m % 4];
}

#define SB_LAYER_MAP(i) osmStored((i)-1)
#include "slicing.glsl"

float osmZ;  // the point's light depth, less the bias

// The opacity at osmZ in texel t (filters read several).
float osmOpacityAt(ivec2 t) {
  osmTexel = t;
  return osmOpacity(osmZ, osmLayout.y);
}
#define SB_FILTER_OPACITY(t) osmOpacityAt(t)
#include "render/common/opacity_filter.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(osmViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, osmParams.x) == 0.0) return 0.0;
  osmZ = lightDistance(osmViewProj, ndc.z - osmParams.x);  // bias in window depth
  float omega = filteredOpacity(uv, int(osmParams.y), osmLayout.w);
  return opacityVisibility(omega / osmParams.w, osmParams.z);
}
