// compute_raster's raster pass: one invocation per segment. The segment is
// clipped at the near plane, projected, and walked along its major screen axis
// one pixel column (or row) at a time; in each column the strand's footprint
// (its width across) covers a run of pixels, each given a
// coverage: analytic (the length of the footprint inside the pixel, a box
// filter across the strand) or binary (pixel centres inside it, as the
// hardware rasterizes the same lines or ribbons). Each covered pixel in front
// of the opaque depth is appended to its tile's list; a full list counts the
// fragment as dropped (SB_CRASTER_COUNT: only counts, to size the lists).
#include "render/common/bindings.glsl"
#include "render/common/invocation.glsl"
#include "compute_raster.glsl"
#include "slots.h"
layout(local_size_x = 64) in;
#ifdef SB_CRASTER_OPAQUE
layout(binding = SB_SLOT_CRASTER_OPAQUE) uniform sampler2D opaqueDepth;
#endif

void emit(uint seg, ivec2 px, float depth, float t, float coverage) {
  if (coverage <= 0.0) return;
#ifdef SB_CRASTER_OPAQUE
  if (depth >= texelFetch(opaqueDepth, px, 0).r) return;
#endif
  uint size = crTiles.z;
  uint tile = uint(px.y) / size * crTiles.x + uint(px.x) / size;
  uint i = atomicAdd(cursor[SB_CR_STATUS_WORDS + tile], 1u);
#ifndef SB_CRASTER_COUNT
  atomicAdd(cursor[SB_CR_GENERATED], 1u);
  uvec2 l = tileLayout[tile];
  if (i >= l.y) {  // the tile's list is full: counted and reported, never silent
    atomicAdd(cursor[SB_CR_DROPPED], 1u);
    return;
  }
  uint local = (uint(px.y) % size) * size + uint(px.x) % size;
  fragments[l.x + i] = uvec4(floatBitsToUint(depth), seg, floatBitsToUint(t),
                             (local << 16) | uint(round(clamp(coverage, 0.0, 1.0) * 65535.0)));
#endif
}

void main() {
  uint seg = linearInvocation();
  if (seg >= crModel.z) return;
#ifndef SB_CRASTER_COUNT
  atomicAdd(cursor[SB_CR_SEGMENTS], 1u);
#endif
  uint first = segments[seg];
  vec4 c0 = toViewClip(points[first].xyz);
  vec4 c1 = toViewClip(points[first + 1u].xyz);
  // Clip at the near plane (window z 0: clip z = 0).
  if (c0.z < 0.0 && c1.z < 0.0) return;
  float ta = 0.0, tb = 1.0;
  if (c0.z < 0.0) ta = c0.z / (c0.z - c1.z);
  if (c1.z < 0.0) tb = c0.z / (c0.z - c1.z);
  vec4 a = mix(c0, c1, ta), b = mix(c0, c1, tb);
  vec2 vp = viewViewport.xy;
  vec3 sa = vec3((a.xy / a.w * 0.5 + 0.5) * vp, a.z / a.w);
  vec3 sb = vec3((b.xy / b.w * 0.5 + 0.5) * vp, b.z / b.w);
  vec2 d = sb.xy - sa.xy;
  float len = length(d);
  if (!(len > 1e-6)) return;  // no extent on screen (or not a number)
  bool xMajor = abs(d.x) >= abs(d.y);
  // Major axis u, minor axis v; A before B along u.
  vec3 A = xMajor ? sa : sa.yxz, B = xMajor ? sb : sb.yxz;
  float wA = a.w, wB = b.w, tA = ta, tB = tb;
  if (A.x > B.x) {
    vec3 s = A; A = B; B = s;
    float w = wA; wA = wB; wB = w;
    float t = tA; tA = tB; tB = t;
  }
  float slope = (B.y - A.y) / (B.x - A.x);
  float cosv = (B.x - A.x) / len;  // >= 1/sqrt(2)
  float width = crStrand.x;
  bool analytic = crModel.x == 0u;
  // The footprint's extent along the minor axis: a strip `width` across
  // (hardware lines: `width` along the minor axis, one pixel per column at 1).
  bool lines = crModel.y == 1u && crModel.w == 0u;
  float h = (analytic || !lines) ? width / cosv : width;
  // width=thickness: the strand's own thickness (world units, per point)
  // projected at each column's depth, so a far strand covers a sliver.
  float thick0 = points[first].w, thick1 = points[first + 1u].w;
  int majorSize = int(xMajor ? vp.x : vp.y), minorSize = int(xMajor ? vp.y : vp.x);
  // Pixel columns whose centre lies in [A.x, B.x): a shared end is drawn once
  // (the hardware's diamond-exit rule differs at the ends, by a column).
  int i0 = int(ceil(A.x - 0.5)), i1 = int(ceil(B.x - 0.5)) - 1;
  i0 = max(i0, 0);
  i1 = min(i1, majorSize - 1);
  for (int i = i0; i <= i1; ++i) {
    float uc = float(i) + 0.5;
    float s = clamp((uc - A.x) / (B.x - A.x), 0.0, 1.0);
    float z = mix(A.z, B.z, s);
    if (z < 0.0 || z > 1.0) continue;
    // Perspective-correct position along the segment (1/w is linear on screen).
    float tl = (s / wB) / ((1.0 - s) / wA + s / wB);
    float t = mix(tA, tB, tl);
    if (crModel.w == 1u) {
      // 1/w is linear on screen; the thickness is linear along the segment.
      float w = 1.0 / mix(1.0 / wA, 1.0 / wB, s);
      width = mix(thick0, thick1, t) * crWidth.x / w;
      h = width / cosv;
    }
    float v = A.y + (uc - A.x) * slope;
    float lo = v - 0.5 * h, hi = v + 0.5 * h;
    int j0 = max(int(floor(lo)), 0), j1 = min(int(floor(hi)), minorSize - 1);
    for (int j = j0; j <= j1; ++j) {
      float vc = float(j) + 0.5;
      float coverage = analytic ? clamp(min(hi, float(j + 1)) - max(lo, float(j)), 0.0, 1.0)
                                : (vc >= lo && vc < hi ? 1.0 : 0.0);
      emit(seg, xMajor ? ivec2(i, j) : ivec2(j, i), z, t, coverage);
    }
  }
}
