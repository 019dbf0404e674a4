// The primary ray of a pixel and the order of hits along it, shared by the
// trace (GLSL) and its tests (rt_oit_math.h, C++ with GLM).
#ifndef SB_INLINE
#define SB_INLINE
#endif

// The world point at NDC (x, y) and window depth z of the view whose inverse
// view-projection is inv.
SB_INLINE vec3 rtoUnproject(mat4 inv, vec2 ndc, float z) {
  vec4 p = inv * vec4(ndc.x, ndc.y, z, 1.0f);
  return vec3(p.x, p.y, p.z) / p.w;
}

// The ray through the centre of pixel px of a width x height frame (rows
// bottom-up, as the accumulation is indexed): it starts on the near plane and
// has |d| = 1, for perspective and orthographic views alike.
SB_INLINE void rtoPrimaryRay(mat4 inv, uvec2 px, uvec2 size, SB_OUT(vec3) o, SB_OUT(vec3) d) {
  vec2 ndc =
      (vec2(float(px.x), float(px.y)) + vec2(0.5f)) / vec2(float(size.x), float(size.y)) * 2.0f -
      vec2(1.0f);
  o = rtoUnproject(inv, ndc, 0.0f);
  d = normalize(rtoUnproject(inv, ndc, 0.5f) - o);
}

// A hit's order key: (t bits, segment). Non-negative floats order like their
// bits; the segment breaks ties, the same on both APIs.
SB_INLINE bool rtoKeyLess(uvec2 a, uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }
