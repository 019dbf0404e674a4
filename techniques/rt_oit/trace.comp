// --oit rt: one invocation per pixel casts the primary ray through the
// pixel's centre into the strand segments, up to the opaque depth: the
// software tier walks the eye BVH (techniques/rt/bvh.h) in this shader, the
// ray-query tier (SB_RT_OIT_RAY_QUERY) asks a ray query over an acceleration
// structure of the segments' boxes (rtoWalk, either way); both hand every
// segment the same test passes to rtoVisit, so they collect the same hits.
// Every hit is shaded at its axis point (the segment's tangent, its colour at
// s) through the shading model and the shadow technique's lookup, and
// composited front to back with its alpha. SB_RT_OIT_K unset: all hits in
// order, each the nearest after the last (one walk per hit, no per-pixel
// memory), at most max_hits (capped pixels counted). SB_RT_OIT_K = k: one
// walk, the k nearest kept sorted and the rest merged in walk order into one
// tail behind them (the k-buffer's math, techniques/kbuffer/kbuffer_math.glsl;
// merged pixels counted): the one place the tiers differ, as their walks meet
// hits in different orders.
#ifdef SB_RT_OIT_RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#include "render/common/bindings.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "render/common/slots.h"
#include "../rt/rt_math.glsl"
#include "slots.h"
#include "uniforms.h"
#define SB_OUT(T) out T
#include "rt_oit_math.glsl"
#ifdef SB_RT_OIT_K
#define SB_INOUT(T) inout T
#define SB_KBUFFER_MAX SB_RT_OIT_K
#include "../kbuffer/kbuffer_math.glsl"
#endif
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SB_SLOT_OIT_ACCUM) writeonly buffer Accum { vec4 accum[]; };
layout(std430, binding = SB_SLOT_RT_OIT_SEGMENTS) readonly buffer RtoSegments {
  vec4 rtoSegments[];
};
// Hits composited, pixels that reached max_hits, pixels with hits merged.
layout(std430, binding = SB_SLOT_RT_OIT_STATUS) buffer RtoStatus { uint rtoStatus[4]; };
#ifdef SB_RT_OIT_OPAQUE
layout(binding = SB_SLOT_RT_OIT_OPAQUE) uniform sampler2D opaqueDepth;
#endif

// The walk's state: how far hits count (the nearest-after search lowers it).
float rtoTMax;

// A hit's shaded colour (rgb, alpha): the segment at BVH slot i, s along it.
vec4 rtoShade(uint i, float s) {
  vec4 a = rtoSegments[2u * i], b = rtoSegments[2u * i + 1u];
  uint first = segments[uint(b.w)];
  vec3 e = b.xyz - a.xyz;
  vec3 tangent = dot(e, e) > 1e-30 ? normalize(e) : vec3(0.0, 1.0, 0.0);
  vec4 c = mix(colors[first], colors[first + 1u], s);
  return vec4(shadeHair(mix(a.xyz, b.xyz, s), tangent, c.rgb), c.a);
}

#ifdef SB_RT_OIT_K
KBuffer rtoKb;
uint rtoHits;
void rtoVisit(uint i, float t, float s) {
  ++rtoHits;
  uvec2 key = uvec2(floatBitsToUint(t), uint(rtoSegments[2u * i + 1u].w));
  kbufferInsert(rtoKb, SB_RT_OIT_K, rtoShade(i, s), key);
}
#else
uvec2 rtoLast, rtoBest;
bool rtoAfterAny;  // false: the first walk, every hit counts
uint rtoBestSlot;
float rtoBestS;
void rtoVisit(uint i, float t, float s) {
  uvec2 key = uvec2(floatBitsToUint(t), uint(rtoSegments[2u * i + 1u].w));
  if (rtoAfterAny && !rtoKeyLess(rtoLast, key)) return;
  if (!rtoKeyLess(key, rtoBest)) return;
  rtoBest = key;
  rtoBestSlot = i;
  rtoBestS = s;
  rtoTMax = t;  // nothing farther can be the nearest
}
#endif

// Whether segment slot i is hit by o + t d (|d| = 1) with 0 < t <= rtoTMax;
// then rtoVisit(i, t, s). Both tiers' one test.
void rtoTest(uint i, vec3 o, vec3 d) {
  vec4 a = rtoSegments[2u * i];
  vec4 b = rtoSegments[2u * i + 1u];
  vec4 h = rtSegmentHit(o, d, a.xyz, b.xyz, a.w);
  if (h.x == 0.0 || h.y <= 0.0 || h.y > rtoTMax) return;
  rtoVisit(i, h.y, h.z);
}

// The traversal: every segment whose cylinder the ray o + t d passes with
// 0 < t <= rtoTMax is handed to rtoVisit(slot, t, s), in the walk's order.
#ifdef SB_RT_OIT_RAY_QUERY
layout(binding = SB_SLOT_RT_OIT_SCENE) uniform accelerationStructureEXT rtoScene;

// The candidates are the boxes the ray meets up to rtoTMax (box i: slot i).
// When rtoVisit lowers rtoTMax (the nearest-after search), a generated
// intersection at it lowers the query's end too, so farther boxes are
// skipped, as the software walk skips them; nothing else is committed.
void rtoWalk(vec3 o, vec3 d) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, rtoScene, gl_RayFlagsNoOpaqueEXT, 0xFF, o, 0.0, d, rtoTMax);
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT)
      continue;
    float before = rtoTMax;
    rtoTest(uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false)), o, d);
    if (rtoTMax < before) rayQueryGenerateIntersectionEXT(q, rtoTMax);
  }
}
#else
layout(std430, binding = SB_SLOT_RT_OIT_NODES) readonly buffer RtoNodes { vec4 rtoNodes[]; };

// Enough for the BVH bvh.h builds (rt's lookup says why).
const int kRtoStack = 48;

void rtoWalk(vec3 o, vec3 d) {
  vec3 invD = rtSafeInverse(d);
  uint stack[kRtoStack];
  int sp = 0;
  stack[sp++] = 0u;
  while (sp > 0) {
    uint n = stack[--sp];
    vec4 lo = rtoNodes[2u * n];
    vec4 hi = rtoNodes[2u * n + 1u];
    if (!rtBoxHit(o, invD, lo.xyz, hi.xyz, rtoTMax)) continue;
    uint first = floatBitsToUint(lo.w);
    uint count = floatBitsToUint(hi.w);
    if (count == 0u) {
      if (sp + 2 <= kRtoStack) {
        stack[sp++] = first;   // right child
        stack[sp++] = n + 1u;  // left child, next in the array
      }
      continue;
    }
    for (uint i = first; i < first + count; ++i) rtoTest(i, o, d);
  }
}
#endif

void main() {
  uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= rtoSize.x || px.y >= rtoSize.y) return;
  vec3 o, d;
  rtoPrimaryRay(rtoInvViewProj, px, rtoSize.xy, o, d);
  // Hits count up to the opaque surface (the raster's depth test), else the far plane.
#ifdef SB_RT_OIT_OPAQUE
  float zEnd = texelFetch(opaqueDepth, ivec2(px), 0).r;
#else
  float zEnd = 1.0;
#endif
  vec2 ndc = (vec2(px) + 0.5) / vec2(rtoSize.xy) * 2.0 - 1.0;
  float tEnd = dot(rtoUnproject(rtoInvViewProj, ndc, zEnd) - o, d);
  uint p = px.y * rtoSize.x + px.x;
#ifdef SB_RT_OIT_K
  rtoKb = kbufferEmpty();
  rtoHits = 0u;
  rtoTMax = tEnd;
  rtoWalk(o, d);
  if (rtoHits > 0u) atomicAdd(rtoStatus[0], rtoHits);
  if (rtoHits > uint(SB_RT_OIT_K)) atomicAdd(rtoStatus[2], 1u);
  accum[p] = kbufferResolve(rtoKb);
#else
  vec3 color = vec3(0.0);
  float T = 1.0;
  uint hits = 0u;
  rtoAfterAny = false;
  for (;;) {
    rtoBest = uvec2(0xFFFFFFFFu);
    rtoTMax = tEnd;
    rtoWalk(o, d);
    if (rtoBest == uvec2(0xFFFFFFFFu)) break;
    vec4 f = rtoShade(rtoBestSlot, rtoBestS);
    color += T * f.a * f.rgb;
    T *= 1.0 - f.a;
    rtoLast = rtoBest;
    rtoAfterAny = true;
    if (++hits == rtoSize.w) {  // max_hits (0: never)
      atomicAdd(rtoStatus[1], 1u);
      break;
    }
  }
  if (hits > 0u) atomicAdd(rtoStatus[0], hits);
  accum[p] = vec4(color, 1.0 - T);
#endif
}
