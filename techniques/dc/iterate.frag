// One k-means step per light texel: each hair fragment joins the cluster with
// the nearest centre and adds (1, z - nearest, (z - nearest)^2) to that
// cluster's channel of the count, sum and square-sum targets (additive).
#include "dc_math.glsl"

layout(binding = 9) uniform sampler2D dcRange;     // x: nearest depth, y: -furthest depth
layout(binding = 13) uniform sampler2D dcCentres;  // one channel per cluster

layout(location = 0) out vec4 outCount;
layout(location = 1) out vec4 outSum;
layout(location = 2) out vec4 outSquares;

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  float zMin = texelFetch(dcRange, t, 0).r;
  float z = gl_FragCoord.z;
  int j = dcNearest(z, texelFetch(dcCentres, t, 0), SB_DC_CLUSTERS);
  float rel = max(z - zMin, 0.0);
  vec4 one = vec4(0.0);
  one[j] = 1.0;
  outCount = one;
  outSum = one * rel;
  outSquares = one * (rel * rel);
}
