// Stochastic transparency (Enderton, Sintorn, Shirley & Luebke 2010,
// "Stochastic Transparency", I3D; TVCG 2011): the math of its passes. Pure
// math, compiled as GLSL and, through stochastic_math.h, as C++ with GLM for
// tests.
//
// The paper's model: S samples per pixel; a fragment of opacity a covers each
// sample with probability a (its random sub-pixel stipple), the depth pass
// keeps per sample the nearest covering depth, so a fragment at depth z passes
// a sample's depth test (z <= stored) with probability prod(1 - a_j) over the
// fragments j in front of it: its visibility, estimated without bias by the
// fraction of samples it passes. The accumulation pass adds (a c, a) where it
// passes (the resolve averages over the samples); the total-alpha pass
// multiplies prod(1 - a) exactly; the alpha correction (section 3.3) scales
// the accumulated colour so its coverage is the exact 1 - prod(1 - a).
#ifndef SB_INLINE
#define SB_INLINE
#endif

// The project's 32-bit integer hash (lowbias32), the same on both APIs.
#include "base/hash.h"

// The coverage mask of a fragment (bit k: sample k of `samples`, at most 32):
// each sample independently with probability alpha, so the expected fraction
// is alpha exactly (alpha 0: no sample; alpha 1: all). `key` names the
// fragment (pixel, primitive, pass group, seed).
SB_INLINE uint stochasticMask(uint key, float alpha, uint samples) {
  uint mask = 0u;
  uint h = hash32(key);
  for (uint k = 0u; k < samples; ++k) {
    h = hash32(h + k * 0x9e3779b9u);
    if (float(h >> 8u) * (1.0f / 16777216.0f) < alpha) mask |= 1u << k;
  }
  return mask;
}

// A fragment's key from its pixel, its primitive, the pass group (several
// groups of MSAA samples make up S) and the seed.
SB_INLINE uint stochasticKey(uint x, uint y, uint primitive, uint group, uint seed) {
  return hash32(x + hash32(y + hash32(primitive + hash32(group + hash32(seed)))));
}

// The composite with alpha correction: accum = (sum of a c vis, sum of a vis)
// averaged over the S samples, t = prod(1 - a) from the total-alpha pass.
// Returns vec4(hair, T) for C = hair + T * C_dst (blend One, SrcAlpha): the
// coverage 1 - T is always the exact one. Where no sample saw any hair
// (accum.w = 0: an empty pixel, t = 1, or an unlucky draw) there is no colour
// to correct: the hair adds nothing, the background keeps its exact T.
SB_INLINE vec4 stochasticResolve(vec4 accum, float t) {
  t = clamp(t, 0.0f, 1.0f);
  // (An overflowed sum, w = inf, has no usable colour either: inf / inf is NaN.)
  if (!(accum.w > 0.0f) || !(accum.w < 3.0e38f)) return vec4(0.0f, 0.0f, 0.0f, t);
  vec3 colour = clamp(vec3(accum.x, accum.y, accum.z) / accum.w, vec3(0.0f), vec3(1.0f));
  return vec4(colour * (1.0f - t), t);
}
