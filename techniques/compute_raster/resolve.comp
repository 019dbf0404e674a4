// compute_raster's resolve, two passes over the tiles (one workgroup per tile,
// one invocation per pixel; the composite reads what the bucket pass wrote in
// another dispatch, so no invocation reads another's buffer writes of the same
// dispatch):
//  - bucket (SB_CRASTER_BUCKET): the tile's list bucketed by pixel, a counting
//    sort through shared memory into the buckets buffer, and each pixel's range;
//  - composite: each pixel takes its fragments front to back, by (depth,
//    segment), each time the nearest after the last (a selection: the list is
//    never fully sorted), compositing them (opacity: the strand's alpha
//    times the coverage) until what is left to see
//    drops under the early-termination transmittance.
#if !defined(SB_CRASTER_BUCKET) && defined(SB_CRASTER_PER_FRAGMENT)
#include "render/common/bindings.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#endif
#include "compute_raster.glsl"
#include "render/common/slots.h"
#include "slots.h"
layout(local_size_x = SB_CRASTER_TILE, local_size_y = SB_CRASTER_TILE) in;
#ifdef SB_CRASTER_BUCKET
layout(std430, binding = SB_SLOT_CRASTER_RANGES) writeonly buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = SB_SLOT_CRASTER_BUCKETS) writeonly buffer Buckets { uvec4 buckets[]; };
shared uint sCount[SB_CRASTER_TILE * SB_CRASTER_TILE];
shared uint sStart[SB_CRASTER_TILE * SB_CRASTER_TILE];
shared uint sFill[SB_CRASTER_TILE * SB_CRASTER_TILE];
#else
layout(std430, binding = SB_SLOT_CRASTER_RANGES) readonly buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = SB_SLOT_CRASTER_BUCKETS) readonly buffer Buckets { uvec4 buckets[]; };
layout(std430, binding = SB_SLOT_OIT_ACCUM) writeonly buffer Accum { vec4 accum[]; };
#ifndef SB_CRASTER_PER_FRAGMENT
layout(std430, binding = SB_SLOT_CRASTER_SHADED) readonly buffer Shaded { vec4 shaded[]; };
#endif
#endif

#ifdef SB_CRASTER_BUCKET
void main() {
  uint tile = gl_WorkGroupID.y * crTiles.x + gl_WorkGroupID.x;
  uint threads = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
  uint tid = gl_LocalInvocationIndex;
  uvec2 l = tileLayout[tile];
  uint counted = cursor[SB_CR_STATUS_WORDS + tile];
  uint n = min(counted, l.y);
  if (tid == 0u) {
    atomicMax(cursor[SB_CR_MAX_TILE], counted);
    if (counted > l.y) atomicAdd(cursor[SB_CR_OVERFLOWED], 1u);
  }
  sCount[tid] = 0u;
  sFill[tid] = 0u;
  barrier();
  for (uint i = tid; i < n; i += threads) atomicAdd(sCount[fragments[l.x + i].w >> 16], 1u);
  barrier();
  uint start = 0u;
  for (uint q = 0u; q < tid; ++q) start += sCount[q];
  sStart[tid] = start;
  barrier();
  for (uint i = tid; i < n; i += threads) {
    uvec4 f = fragments[l.x + i];
    uint q = f.w >> 16;
    buckets[l.x + sStart[q] + atomicAdd(sFill[q], 1u)] = f;
  }
  uvec2 px = gl_WorkGroupID.xy * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
  if (px.x < crSize.x && px.y < crSize.y) ranges[px.y * crSize.x + px.x] = uvec2(l.x + start, sCount[tid]);
}
#else
// Within one pixel (depth bits, segment) orders every fragment: a segment
// covers a pixel once.
bool keyLess(uvec2 a, uvec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }

vec4 fragmentColor(uvec4 f) {
  uint seg = f.y;
  float t = uintBitsToFloat(f.z);
#ifdef SB_CRASTER_PER_FRAGMENT
  uint first = segments[seg];
  vec3 p0 = points[first].xyz, p1 = points[first + 1u].xyz;
  vec3 d = p1 - p0;
  vec3 tangent = dot(d, d) > 1e-30 ? normalize(d) : vec3(0.0, 1.0, 0.0);
  vec4 c = mix(colors[first], colors[first + 1u], t);
  return vec4(shadeHair(mix(p0, p1, t), tangent, c.rgb), c.a);
#else
  return mix(shaded[2u * seg], shaded[2u * seg + 1u], t);
#endif
}

void main() {
  uvec2 px = gl_WorkGroupID.xy * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
  if (px.x >= crSize.x || px.y >= crSize.y) return;
  uint pixel = px.y * crSize.x + px.x;
  uvec2 r = ranges[pixel];
  vec4 acc = vec4(0.0);
  uvec2 last = uvec2(0u);
  for (uint taken = 0u; taken < r.y; ++taken) {
    // The nearest fragment after the last one taken.
    uint best = 0u;
    uvec2 bestKey = uvec2(0xFFFFFFFFu);
    for (uint k = 0u; k < r.y; ++k) {
      uvec4 f = buckets[r.x + k];
      if ((taken == 0u || keyLess(last, f.xy)) && keyLess(f.xy, bestKey)) {
        best = k;
        bestKey = f.xy;
      }
    }
    last = bestKey;
    uvec4 f = buckets[r.x + best];
    vec4 c = fragmentColor(f);
    float a = c.a * float(f.w & 0xFFFFu) * (1.0 / 65535.0);
    acc += (1.0 - acc.a) * vec4(c.rgb * a, a);
    if (1.0 - acc.a < crStrand.w) {
      atomicAdd(cursor[SB_CR_TERMINATED], 1u);
      break;
    }
  }
  accum[pixel] = acc;
}
#endif
