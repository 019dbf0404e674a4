// TressFX ShortCut's resolve (AMD TressFX 4), as the issue extends it: the k
// nearest fragments composited in depth order (near, tNear = prod(1 - a) of
// them), and behind them the tail, all other fragments, as TressFX's weighted
// average: colour sum(c a) / sum(a) with the tail's coverage 1 - tAll / tNear
// (tAll: the product of (1 - a) over every fragment, from the revealage
// target). Returns vec4(hair, T) for C = hair + T C_dst. Pure math, compiled
// as GLSL and, through shortcut_math.h, as C++ with GLM for tests.
#ifndef SB_INLINE
#define SB_INLINE
#endif

SB_INLINE vec4 shortcutResolve(vec3 near, float tNear, vec4 tailSum, float tAll) {
  float t = clamp(tAll, 0.0f, 1.0f);
  vec3 avg = tailSum.w > 0.0f ? vec3(tailSum.x, tailSum.y, tailSum.z) / tailSum.w : vec3(0.0f);
  avg = clamp(avg, vec3(0.0f), vec3(1.0f));
  // Tail transmittance; tNear near 0 hides the tail anyway.
  float tTail = tNear > 1e-20f ? clamp(t / tNear, 0.0f, 1.0f) : 1.0f;
  return vec4(near + tNear * (1.0f - tTail) * avg, t);
}
