// Deep opacity maps' layers (Yuksel & Keyser 2008): their sizes, the depth
// quantization and what a fragment adds to each, over the shared opacity math
// (render/common/opacity.glsl). Pure math, compiled as GLSL and, through
// layers.h, as C++ for CPU tests.
#ifndef SB_DOM_LAYERS_GLSL
#define SB_DOM_LAYERS_GLSL
#include "render/common/opacity.glsl"

// Layer spacings of deep opacity maps (slides: constant, linear, powers of 2,
// Fibonacci); a list is given explicitly on the CPU.
const int kDomConstant = 0;
const int kDomLinear = 1;
const int kDomPow2 = 2;
const int kDomFibonacci = 3;
// Unreal's hair deep opacity maps place their layers at clip-space depths
// 0.01, 0.05, 0.2, 0.5 behind the front depth (HairStrandsDeepShadowCommon.ush):
// close to a power law d_k = D (k/K)^p with p = 2.8 (0.011, 0.07, 0.22, 0.5
// for K = 4 and D = 0.5). spacing=power: that law with D = K s.
const int kDomPower = 4;
const float kDomPowerExponent = 2.8f;

// What happens to fragments beyond the last layer (paper Sec. 3).
const int kDomIgnore = 0;
const int kDomLast = 1;
const int kDomExtend = 2;

// Size of DOM layer k (1..K) for layer size s.
SB_INLINE float domLayerSize(int k, int spacing, float s) {
  // (the power law needs K: domPowerLayerSize)
  if (spacing == kDomLinear) return s * float(k);
  if (spacing == kDomPow2) return s * exp2(float(k - 1));
  if (spacing == kDomFibonacci) {
    float a = 1.0f;
    float b = 1.0f;
    for (int i = 1; i < k; ++i) {
      float c = a + b;
      a = b;
      b = c;
    }
    return s * a;
  }
  return s;
}

// Size of layer k (1..K) of K under spacing=power: K s ((k/K)^p - ((k-1)/K)^p).
SB_INLINE float domPowerLayerSize(int k, int K, float s) {
  float a = pow(float(k) / float(K), kDomPowerExponent);
  float b = pow(float(k - 1) / float(K), kDomPowerExponent);
  return float(K) * s * (a - b);
}

// Depth quantized to `bits` (8, 16; 32 keeps it), rounded down so the first
// fragment of a texel never lies in front of its own z0.
SB_INLINE float domQuantize(float z, int bits) {
  if (bits >= 32) return z;
  float levels = exp2(float(bits)) - 1.0f;
  return floor(clamp(z, 0.0f, 1.0f) * levels) / levels;
}

#ifdef SB_LAYER_BOUND
// SB_LAYER_BOUND(k) (the layered maps' accessors: render/common/layered_glsl.h):
// layer boundary d_k (k = 0..K, d_0 = 0, increasing), relative
// to the texel's first hair depth z0. Layer k lies in [z0 + d_(k-1), z0 + d_k).

// What a fragment dz = z - z0 behind the first hair adds to layer k: it counts
// in its own layer and every layer behind it; beyond the last layer it is
// ignored, or counted in the last layer (kDomLast). kDomExtend has its
// boundaries stretched on the CPU to cover the hair.
SB_INLINE float domContribution(float dz, int k, int K, int beyond) {
  return (dz < SB_LAYER_BOUND(k) || (beyond == kDomLast && k == K)) ? 1.0f : 0.0f;
}

// The thesis's counting (Kraft 2018, Listing 3): a fragment counts in its own
// layer and every layer in front of it, so layer k holds the fragments at or
// behind its start d_(k-1) (layer 1 all of them). Beyond the last layer it is
// ignored, or (kDomLast) counted in every layer, as the listing does.
SB_INLINE float domContributionPreceding(float dz, int k, int K, int beyond) {
  if (k < 1 || k > K) return 0.0f;
  if (!(dz < SB_LAYER_BOUND(K)) && beyond != kDomLast) return 0.0f;
  return dz >= SB_LAYER_BOUND(k - 1) ? 1.0f : 0.0f;
}

#ifdef SB_LAYER_MAP
// Opacity at depth z in a texel whose hair starts at z0, from K layers;
// SB_LAYER_MAP(k) (k = 1..K) is layer k's accumulated opacity. Interpolated
// within the layer holding z (0 at z0); beyond the last layer the last value.
SB_INLINE float domOpacity(float z, float z0, int K) {
  if (!(z >= z0) || K < 1) return 0.0f;
  float dz = z - z0;
  float prev = 0.0f;
  for (int k = 1; k <= K; ++k) {
    float cur = SB_LAYER_MAP(k);
    if (dz < SB_LAYER_BOUND(k))
      return opacityLerp(dz, SB_LAYER_BOUND(k - 1), SB_LAYER_BOUND(k), prev, cur);
    prev = cur;
  }
  return prev;
}
#endif
#endif
#endif  // SB_DOM_LAYERS_GLSL
