// The cluster centres of every light texel (a pass over the map, one channel
// per cluster, 4 per layer): spread over the depth range at first
// (SB_DC_FIRST), then the mean depth of each cluster's fragments (k-means
// update).
#include "dc_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_DC_RANGE) uniform sampler2D dcRange;  // x: nearest, y: -furthest depth
#if !SB_DC_FIRST
// Per cluster: fragments, sum of (z - nearest)
layout(binding = SB_SLOT_DC_COUNTS) uniform sampler2DArray dcCounts;
layout(binding = SB_SLOT_DC_SUMS) uniform sampler2DArray dcSums;
#endif

layout(location = 0) out vec4 outCentres[SB_DC_LAYERS];

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  vec2 r = texelFetch(dcRange, t, 0).rg;
  for (int l = 0; l < SB_DC_LAYERS; ++l) {
    vec4 c = vec4(0.0);
#if !SB_DC_FIRST
    vec4 n = texelFetch(dcCounts, ivec3(t, l), 0);
    vec4 s1 = texelFetch(dcSums, ivec3(t, l), 0);
#endif
    for (int i = 0; i < 4 && 4 * l + i < SB_DC_CLUSTERS; ++i) {
      c[i] = dcInitialCentre(4 * l + i, SB_DC_CLUSTERS, r.x, -r.y);
#if !SB_DC_FIRST
      c[i] = dcCentre(n[i], s1[i], r.x, c[i]);  // an empty cluster starts again from its spread
#endif
    }
    outCentres[l] = c;
  }
}
