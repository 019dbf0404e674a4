// The cluster centres of every light texel (a pass over the map, one channel
// per cluster): spread over the depth range at first (SB_DC_FIRST), then the
// mean depth of each cluster's fragments (k-means update).
#include "dc_math.glsl"

layout(binding = 9) uniform sampler2D dcRange;  // x: nearest depth, y: -furthest depth
#if !SB_DC_FIRST
layout(binding = 10) uniform sampler2D dcCounts;  // fragments per cluster
layout(binding = 11) uniform sampler2D dcSums;    // sum of (z - nearest) per cluster
#endif

layout(location = 0) out vec4 outCentres;

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  vec2 r = texelFetch(dcRange, t, 0).rg;
  vec4 c = vec4(0.0);
#if !SB_DC_FIRST
  vec4 n = texelFetch(dcCounts, t, 0);
  vec4 s1 = texelFetch(dcSums, t, 0);
#endif
  for (int j = 0; j < SB_DC_CLUSTERS; ++j) {
    c[j] = dcInitialCentre(j, SB_DC_CLUSTERS, r.x, -r.y);
#if !SB_DC_FIRST
    c[j] = dcCentre(n[j], s1[j], r.x, c[j]);  // an empty cluster starts again from its spread
#endif
  }
  outCentres = c;
}
