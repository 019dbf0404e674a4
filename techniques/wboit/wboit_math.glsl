// Weighted blended order-independent transparency (McGuire & Bavoil 2013,
// JCGT 2(2)): the depth weights and the resolve. Pure math, compiled as GLSL
// and, through wboit_math.h, as C++ with GLM for tests.
//
// Accumulation (additive): accum += (c_i a_i w_i, a_i w_i), w_i = w(z_i, a_i);
// revealage (blend Zero, OneMinusSrcColor, cleared to 1): r *= (1 - a_i).
// Resolve (the paper's eq. 6):
//   C = accum.rgb / max(accum.a, 1e-5) * (1 - r) + C_dst * r.
#ifndef SB_INLINE
#define SB_INLINE
#endif

// Weight functions; z: view-space depth (distance along the view direction,
// scene units), d: window depth gl_FragCoord.z in [0,1], a: coverage.
//   0 const: w = 1 (eq. 6 with no depth weight)
//   7: w = a * clamp(10 / (1e-5 + (|z|/5)^2 + (|z|/200)^6), 1e-2, 3e3)
//   8: w = a * clamp(10 / (1e-5 + (|z|/10)^3 + (|z|/200)^6), 1e-2, 3e3)
//   9: w = a * clamp(0.03 / (1e-5 + (|z|/200)^4), 1e-2, 3e3)
//  10: w = a * max(1e-2, 3e3 * (1 - d)^3)
SB_INLINE float wboitWeight(int eq, float z, float d, float a) {
  float az = abs(z);
  if (eq == 7)
    return a * clamp(10.0f / (1e-5f + pow(az / 5.0f, 2.0f) + pow(az / 200.0f, 6.0f)), 1e-2f,
                     3e3f);
  if (eq == 8)
    return a * clamp(10.0f / (1e-5f + pow(az / 10.0f, 3.0f) + pow(az / 200.0f, 6.0f)), 1e-2f,
                     3e3f);
  if (eq == 9) return a * clamp(0.03f / (1e-5f + pow(az / 200.0f, 4.0f)), 1e-2f, 3e3f);
  if (eq == 10) {
    float e = 1.0f - clamp(d, 0.0f, 1.0f);
    return a * max(1e-2f, 3e3f * e * e * e);
  }
  return 1.0f;
}

// Returns vec4(hair, T) for the composite C = hair + T * C_dst. A 16-bit
// accumulation can overflow to +inf; min(., 3e38) turns inf into a large finite
// value (all-inf gives colour 1, the paper's "suppress overflow"), so no NaN.
// An empty pixel (accum 0, r 1) gives (0, 1): the background unchanged.
SB_INLINE vec4 wboitResolve(vec4 accum, float revealage) {
  vec3 sumC = min(vec3(accum.x, accum.y, accum.z), vec3(3e38f));
  float sumA = min(accum.w, 3e38f);
  vec3 avg = clamp(sumC / max(sumA, 1e-5f), vec3(0.0f), vec3(1.0f));
  float t = clamp(revealage, 0.0f, 1.0f);
  return vec4(avg * (1.0f - t), t);
}
