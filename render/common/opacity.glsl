// Opacity-based self-shadowing math shared by opacity shadow maps (Kim &
// Neumann 2001) and deep opacity maps (Yuksel & Keyser 2008). Pure math,
// compiled as GLSL and, through opacity.h, as C++ with GLM for CPU tests; each
// technique's own (OSM's slicing, DOM's layers) lives in its folder.
//
// One definition of opacity: every hair fragment has opacity alpha_s, maps
// accumulate fragment counts n (or n * w with a per-fragment weight w), and
// visibility is (1 - alpha_s)^n. The papers' exp(-kappa * Omega) with
// Omega = n * w is the same function when w = -ln(1 - alpha_s) / kappa.
// Depths are the light's window depths in [0,1] (light depth units).
#ifndef SB_OPACITY_GLSL
#define SB_OPACITY_GLSL
#ifndef SB_INLINE
#define SB_INLINE
#endif

// (1 - alpha_s)^n, with pow(0, 0) guarded: no fragment in front is fully lit.
SB_INLINE float opacityVisibility(float n, float alphaS) {
  if (!(n > 0.0f)) return 1.0f;  // also NaN
  if (!(alphaS > 0.0f)) return 1.0f;
  if (alphaS >= 1.0f) return 0.0f;
  return clamp(pow(1.0f - alphaS, n), 0.0f, 1.0f);
}

// Opacity linearly interpolated between o0 at depth z0 and o1 at z1
// (OSM footnote 5); an empty interval gives o1.
SB_INLINE float opacityLerp(float z, float z0, float z1, float o0, float o1) {
  float t = z1 > z0 ? clamp((z - z0) / (z1 - z0), 0.0f, 1.0f) : 1.0f;
  return o0 + t * (o1 - o0);
}
#endif  // SB_OPACITY_GLSL
