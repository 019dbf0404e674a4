// Ray-traced strand shadows, software tier: from the point, rays to the light
// through a BVH of the strand segments (built on the CPU, techniques/rt/bvh.h),
// walked with a stack in shader code. Every segment crossed nearer the light
// than the point (its axis's light depth below the point's minus the bias, the
// exact reference's rule) multiplies the ray's transmittance by
// (1 - shadow_alpha); the visibility is the mean over the rays. The opaque
// mesh casts its hard shadow through its depth map, as in every technique.
#include "../common/opaque_shadow.glsl"
#include "slots.h"
#include "uniforms.h"
#include "rt_math.glsl"

layout(std430, binding = SB_SLOT_RT_NODES) readonly buffer RtNodes { vec4 rtNodes[]; };
layout(std430, binding = SB_SLOT_RT_SEGMENTS) readonly buffer RtSegments { vec4 rtSegments[]; };
// x: rays that reached max_hits (the counter rt.max_hits_reached).
layout(std430, binding = SB_SLOT_RT_STATUS) buffer RtStatus { uint rtCapped; };

// Enough for the BVH bvh.h builds: at most 24 SAH levels, then balanced median
// splits (depth <= 24 + log2(segments) + 2).
const int kRtStack = 48;

// Transmittance along o + t d, t in (0, tMax), over segments whose axis point
// lies in front of the light depth zLimit.
float rtTransmittance(vec3 o, vec3 d, float tMax, float zLimit) {
  float keep = 1.0 - rtParams.z;
  uint maxHits = uint(rtAxisU.w);
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
    for (uint i = first; i < first + count; ++i) {
      vec4 a = rtSegments[2u * i];
      vec4 b = rtSegments[2u * i + 1u];
      vec4 h = rtSegmentHit(o, d, a.xyz, b.xyz, a.w);
      if (h.x == 0.0 || h.y <= 0.0 || h.y >= tMax) continue;
      vec3 axisPoint = mix(a.xyz, b.xyz, h.z);
      vec4 c = clipOf(rtViewProj, axisPoint);
      if (c.z / c.w >= zLimit) continue;  // the point's own strand, or behind it
      T *= keep;
      if (++hits == maxHits) {
#ifdef SB_RT_COUNT_CAP
        // Only with a cap: a store turns off early depth tests in the hair
        // pass, and every hidden fragment then walks the BVH (20x the time on
        // stray:strands=3000 at 128x128, llvmpipe).
        atomicAdd(rtCapped, 1u);
#endif
        return T;
      }
    }
  }
  return T;
}

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(rtViewProj, worldPos, ndc)) return 1.0;
  if (opaqueVisibility(ndc, rtParams.x) == 0.0) return 0.0;
  float zLimit = max(ndc.z - rtParams.x, 0.0);
  // One light texel at the point, in world units, for the rays' offsets.
  float texel = rtAxisV.w * clipOf(rtViewProj, worldPos).w;
  int rays = int(rtParams.w);
  float sum = 0.0;
  for (int k = 0; k < rays; ++k) {
    vec2 j = rtJitter(k, rays) * texel;
    vec3 o = worldPos + j.x * rtAxisU.xyz + j.y * rtAxisV.xyz;
    vec3 toLight = rtLight.w > 0.5 ? rtLight.xyz - o : rtLight.xyz;
    float tMax = rtLight.w > 0.5 ? length(toLight) : 3.0e38;
    sum += rtTransmittance(o, normalize(toLight), tMax, zLimit);
  }
  return sum / float(rays);
}
