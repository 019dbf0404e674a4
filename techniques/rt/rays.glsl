// Ray-traced strand shadows, both tiers: the rays from a point to the light
// (shadowVisibility) and the rule for a segment they cross (rtCrosses); each
// tier's lookup defines rtTransmittance, the walk over the segments a ray may
// cross (lookup.glsl: a BVH in shader code; lookup_ray_query.glsl: ray queries
// over an acceleration structure of the segments' boxes).
// Every segment crossed nearer the light than the point (its axis's light
// depth below the point's minus the bias, the exact reference's rule)
// multiplies the ray's transmittance by (1 - shadow_alpha); the visibility is
// the mean over the rays. The opaque mesh casts its hard shadow through its
// depth map, as in every technique.
#include "render/common/opaque_shadow.glsl"
#include "rt_math.glsl"
#include "slots.h"
#include "uniforms.h"

layout(std430, binding = SB_SLOT_RT_SEGMENTS) readonly buffer RtSegments { vec4 rtSegments[]; };
// x: rays that reached max_hits (the counter rt.max_hits_reached).
layout(std430, binding = SB_SLOT_RT_STATUS) buffer RtStatus { uint rtCapped; };

// Whether segment i (of rtSegments) is crossed by o + t d, t in (0, tMax),
// at an axis point in front of the light depth zLimit.
bool rtCrosses(uint i, vec3 o, vec3 d, float tMax, float zLimit) {
  vec4 a = rtSegments[2u * i];
  vec4 b = rtSegments[2u * i + 1u];
  vec4 h = rtSegmentHit(o, d, a.xyz, b.xyz, a.w);
  if (h.x == 0.0 || h.y <= 0.0 || h.y >= tMax) return false;
  vec4 c = clipOf(rtViewProj, mix(a.xyz, b.xyz, h.z));
  return c.z / c.w < zLimit;  // else the point's own strand, or behind it
}

// One more strand crossed: T loses its share; true when the ray stops there
// (max_hits).
bool rtCross(inout float T, inout uint hits) {
  T *= 1.0 - rtParams.z;
  if (++hits != uint(rtAxisU.w)) return false;
#ifdef SB_RT_COUNT_CAP
  // Only with a cap: a store turns off early depth tests in the hair pass, and
  // every hidden fragment then walks the segments (20x the time on
  // stray:strands=3000 at 128x128, llvmpipe).
  atomicAdd(rtCapped, 1u);
#endif
  return true;
}

// Transmittance along o + t d, t in (0, tMax), over the segments rtCrosses
// accepts: the tier's walk.
float rtTransmittance(vec3 o, vec3 d, float tMax, float zLimit);

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
