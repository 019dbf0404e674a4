// Resolve math of the weighted sum and weighted average transparency
// approximations (Bavoil & Myers 2008, "Order independent transparency with
// dual depth peeling", section "weighted sum" / "weighted average"). Pure math,
// compiled as GLSL and, through weighted_math.h, as C++ with GLM for tests.
//
// Both return vec4(hair, T): the hair's contribution, already multiplied by its
// coverage, and the transmittance T of the background, so the composite is
//   C = hair + T * C_dst
// (blend One, SrcAlpha in the resolve pass). For inputs in [0,1], hair, T and C
// stay in [0,1]; an empty pixel gives (0, 1): the background unchanged.
#ifndef SB_INLINE
#define SB_INLINE
#endif

// Weighted sum (Meshkin 2007 as written by Bavoil & Myers 2008):
//   C = sum(a_i c_i) + C_dst * (1 - sum(a_i)).
// accum = (sum a_i c_i, sum a_i). The unbounded sums are saturated the way the
// original's 8-bit framebuffer saturated them: T = max(0, 1 - sum a) and the
// colour sum min(., 1). While sum a < 1, sum a c <= sum a, so C <= 1 already.
SB_INLINE vec4 weightedSumResolve(vec4 accum) {
  float t = max(0.0f, 1.0f - accum.w);
  vec3 hair = clamp(vec3(accum.x, accum.y, accum.z), vec3(0.0f), vec3(1.0f));
  return vec4(hair, t);
}

// Weighted average (Bavoil & Myers 2008):
//   avgColor = sum(a_i c_i) / sum(a_i), avgAlpha = sum(a_i) / n,
//   T = (1 - avgAlpha)^n,  C = avgColor * (1 - T) + C_dst * T.
// accum = (sum a_i c_i, sum a_i), n = the fragment count. Guards: n = 0 or
// sum a = 0 leaves the background (T = 1); avgAlpha = 1 gives T = 0 exactly.
SB_INLINE vec4 weightedAverageResolve(vec4 accum, float n) {
  if (n < 0.5f || accum.w <= 0.0f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  vec3 avgColor = clamp(vec3(accum.x, accum.y, accum.z) / accum.w, vec3(0.0f), vec3(1.0f));
  float avgAlpha = clamp(accum.w / n, 0.0f, 1.0f);
  float t = avgAlpha >= 1.0f ? 0.0f : pow(1.0f - avgAlpha, n);
  return vec4(avgColor * (1.0f - t), t);
}
