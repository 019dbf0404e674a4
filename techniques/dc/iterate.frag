// One k-means step per light texel: each hair fragment joins the cluster with
// the nearest centre and adds (1, z - nearest, (z - nearest)^2) to that
// cluster's channel of the count, sum and square-sum targets (additive); the
// targets are the layers of the three arrays, 4 clusters per layer.
#include "dc_math.glsl"
#include "slots.h"
#include "render/common/light_pass_depth.glsl"

layout(binding = SB_SLOT_DC_RANGE) uniform sampler2D dcRange;  // x: nearest, y: -furthest depth
layout(binding = SB_SLOT_DC_CENTRES) uniform sampler2DArray dcCentres;  // one channel per cluster

// Counts at 0.., sums at SB_DC_LAYERS.., square sums at 2 * SB_DC_LAYERS...
layout(location = 0) out vec4 outMaps[3 * SB_DC_LAYERS];

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  float zMin = texelFetch(dcRange, t, 0).r;
  float z = passDepth();
  // The nearest centre of each layer's clusters, then the nearest of those
  // (ties: the lower index, as within a layer).
  int layer = 0;
  int j = dcNearest(z, texelFetch(dcCentres, ivec3(t, 0), 0), min(SB_DC_CLUSTERS, 4));
  float best = abs(z - texelFetch(dcCentres, ivec3(t, 0), 0)[j]);
  for (int l = 1; l < SB_DC_LAYERS; ++l) {
    vec4 c = texelFetch(dcCentres, ivec3(t, l), 0);
    int i = dcNearest(z, c, min(SB_DC_CLUSTERS - 4 * l, 4));
    if (abs(z - c[i]) < best) {
      best = abs(z - c[i]);
      layer = l;
      j = i;
    }
  }
  float rel = max(z - zMin, 0.0);
  vec4 one = vec4(0.0);
  one[j] = 1.0;
  for (int l = 0; l < SB_DC_LAYERS; ++l) {
    vec4 mine = l == layer ? one : vec4(0.0);
    outMaps[l] = mine;
    outMaps[SB_DC_LAYERS + l] = mine * rel;
    outMaps[2 * SB_DC_LAYERS + l] = mine * (rel * rel);
  }
}
