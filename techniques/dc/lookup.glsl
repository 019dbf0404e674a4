// Density clustering (Mertens et al. 2004): the hair fragments in front of a
// point are the sum over its light texel's clusters of each cluster's count
// times the part of its extent [mean - sqrt(3) sd, mean + sqrt(3) sd] in front
// (dc_math.glsl); visibility (1 - alpha_s)^n, times the opaque mesh's hard
// shadow. Textures only, fetched without derivatives.
#include "render/common/opaque_shadow.glsl"
#include "dc_math.glsl"
#include "slots.h"

#include "uniforms.h"
layout(binding = SB_SLOT_DC_RANGE) uniform sampler2D dcRange;  // x: nearest, y: -furthest depth
// 4 clusters per layer: fragments, sum of (z - nearest), sum of (z - nearest)^2
layout(binding = SB_SLOT_DC_COUNTS) uniform sampler2DArray dcCounts;
layout(binding = SB_SLOT_DC_SUMS) uniform sampler2DArray dcSums;
layout(binding = SB_SLOT_DC_SQUARES) uniform sampler2DArray dcSquares;

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(dcViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float bias = dcParams.x;
  if (opaqueVisibility(ndc, bias) == 0.0) return 0.0;
  int size = int(dcParams.y);
  ivec2 t = clamp(ivec2(floor(uv * dcParams.y)), ivec2(0), ivec2(size - 1));
  vec2 r = texelFetch(dcRange, t, 0).rg;
  float zLight = lightDistance(dcViewProj, ndc.z - bias);  // bias in window depth
  float n = 0.0;
  for (int l = 0; l < SB_DC_LAYERS; ++l) {
    ivec3 p = ivec3(t, l);
    n += dcCount(zLight, r.x, -r.y, texelFetch(dcCounts, p, 0), texelFetch(dcSums, p, 0),
                 texelFetch(dcSquares, p, 0), min(SB_DC_CLUSTERS - 4 * l, 4));
  }
  return dcVisibility(n, dcParams.z);
}
