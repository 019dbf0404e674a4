// Opacity shadow maps lookup: the point's opacity interpolated between the
// two maps enclosing its light depth (opacity.glsl), visibility
// (1 - alpha_s)^(opacity / weight); 0 behind the opaque mesh.
#include "../common/opaque_shadow.glsl"
#include "osm.glsl"

layout(binding = 9) uniform sampler2D osmAtlas0;
#if SB_OSM_ATLASES > 1
layout(binding = 10) uniform sampler2D osmAtlas1;
#endif
#if SB_OSM_ATLASES > 2
layout(binding = 11) uniform sampler2D osmAtlas2;
#endif
#if SB_OSM_ATLASES > 3
layout(binding = 12) uniform sampler2D osmAtlas3;
#endif
#if SB_OSM_ATLASES > 4
layout(binding = 13) uniform sampler2D osmAtlas4;
#endif
#if SB_OSM_ATLASES > 5
layout(binding = 14) uniform sampler2D osmAtlas5;
#endif

ivec2 osmTexel;  // the point's texel within a tile

// Stored map m (= map m + 1): texel group m / 4 is tile g / atlases of atlas g % atlases.
float osmStored(int m) {
  int g = m / 4;
  int a = g % osmLayout.z;
  int t = g / osmLayout.z;
  ivec2 p = osmTexel + ivec2(t % osmLayout.x, t / osmLayout.x) * int(osmParams.y);
  vec4 v = texelFetch(osmAtlas0, p, 0);
#if SB_OSM_ATLASES > 1
  if (a == 1) v = texelFetch(osmAtlas1, p, 0);
#endif
#if SB_OSM_ATLASES > 2
  if (a == 2) v = texelFetch(osmAtlas2, p, 0);
#endif
#if SB_OSM_ATLASES > 3
  if (a == 3) v = texelFetch(osmAtlas3, p, 0);
#endif
#if SB_OSM_ATLASES > 4
  if (a == 4) v = texelFetch(osmAtlas4, p, 0);
#endif
#if SB_OSM_ATLASES > 5
  if (a == 5) v = texelFetch(osmAtlas5, p, 0);
#endif
  return v[m % 4];
}

#define SB_OSM_MAP(i) osmStored((i) - 1)
#include "../common/opacity.glsl"

float shadowVisibility(vec3 worldPos) {
  vec4 clip = osmViewProj * vec4(worldPos, 1.0);
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  if (opaqueVisibility(ndc, osmParams.x) == 0.0) return 0.0;
  int size = int(osmParams.y);
  osmTexel = min(ivec2(uv * osmParams.y), ivec2(size - 1));
  float omega = osmOpacity(ndc.z - osmParams.x, osmLayout.y);
  return opacityVisibility(omega / osmParams.w, osmParams.z);
}
