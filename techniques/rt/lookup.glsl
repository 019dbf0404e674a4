// Ray-traced strand shadows, software tier: the segments a ray crosses found
// by walking a BVH (built on the CPU, techniques/rt/bvh.h) with a stack in
// shader code. The rays and the rule for a crossing: rays.glsl.
#include "rays.glsl"
#include "slots.h"

layout(std430, binding = SB_SLOT_RT_NODES) readonly buffer RtNodes { vec4 rtNodes[]; };

// Enough for the BVH bvh.h builds: at most 24 SAH levels, then balanced median
// splits (depth <= 24 + log2(segments) + 2).
const int kRtStack = 48;

float rtTransmittance(vec3 o, vec3 d, float tMax, float zLimit) {
  vec3 invD = rtSafeInverse(d);
  float T = 1.0;
  uint hits = 0u;
  uint stack[kRtStack];
  int sp = 0;
  stack[sp++] = 0u;
  while (sp > 0) {
    uint n = stack[--sp];
    vec4 lo = rtNodes[2u * n];
    vec4 hi = rtNodes[2u * n + 1u];
    if (!rtBoxHit(o, invD, lo.xyz, hi.xyz, tMax)) continue;
    uint first = floatBitsToUint(lo.w);
    uint count = floatBitsToUint(hi.w);
    if (count == 0u) {
      if (sp + 2 <= kRtStack) {
        stack[sp++] = first;   // right child
        stack[sp++] = n + 1u;  // left child, next in the array
      }
      continue;
    }
    for (uint i = first; i < first + count; ++i)
      if (rtCrosses(i, o, d, tMax, zLimit) && rtCross(T, hits)) return T;
  }
  return T;
}
