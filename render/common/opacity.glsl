// Opacity-based self-shadowing math shared by opacity shadow maps (Kim &
// Neumann 2001) and deep opacity maps (Yuksel & Keyser 2008). Pure math,
// compiled as GLSL and, through opacity.h, as C++ with GLM for CPU tests.
//
// One definition of opacity: every hair fragment has opacity alpha_s, maps
// accumulate fragment counts n (or n * w with a per-fragment weight w), and
// visibility is (1 - alpha_s)^n. The papers' exp(-kappa * Omega) with
// Omega = n * w is the same function when w = -ln(1 - alpha_s) / kappa.
// Depths are the light's window depths in [0,1] (light depth units).
#ifndef SB_INLINE
#define SB_INLINE
#endif

// Slicing schemes of opacity shadow maps (paper Fig. 3); density is placed on
// the CPU from the hair's depth distribution (opacity.h).
const int kOsmUniform = 0;
const int kOsmDensity = 1;
const int kOsmGamma = 2;

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

// Depth D_i of OSM slice i in 0..n between the hair's near and far depth:
// uniform, or gamma (tighter near the light, where shadows vary most).
SB_INLINE float osmSliceDepth(int i, int n, float nearZ, float farZ, int mode, float gamma) {
  float f = float(i) / float(max(n, 1));
  if (mode == kOsmGamma) f = pow(f, gamma);
  return nearZ + (farZ - nearZ) * f;
}

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

#ifdef SB_OSM_SLICE
// Opacity at depth z from n opacity maps. The includer defines
// SB_OSM_SLICE(i): depth D_i (i = 0..n, increasing, D_0 = the hair's near
// depth) and SB_OSM_MAP(i): map i (1..n), the opacity of the fragments in
// front of D_i; map 0 is 0. Linear interpolation between the two maps
// enclosing z; beyond D_n the last map.
SB_INLINE float osmOpacity(float z, int n) {
  if (n < 1 || !(z >= SB_OSM_SLICE(0))) return 0.0f;
  if (z >= SB_OSM_SLICE(n)) return SB_OSM_MAP(n);
  int lo = 1;
  int hi = n;
  while (lo < hi) {  // smallest i with z < D_i
    int mid = (lo + hi) / 2;
    if (z < SB_OSM_SLICE(mid))
      hi = mid;
    else
      lo = mid + 1;
  }
  float prev = lo > 1 ? SB_OSM_MAP(lo - 1) : 0.0f;
  return opacityLerp(z, SB_OSM_SLICE(lo - 1), SB_OSM_SLICE(lo), prev, SB_OSM_MAP(lo));
}
#endif

#ifdef SB_DOM_D
// SB_DOM_D(k): layer boundary d_k (k = 0..K, d_0 = 0, increasing), relative
// to the texel's first hair depth z0. Layer k lies in [z0 + d_(k-1), z0 + d_k).

// What a fragment dz = z - z0 behind the first hair adds to layer k: it counts
// in its own layer and every layer behind it; beyond the last layer it is
// ignored, or counted in the last layer (kDomLast). kDomExtend has its
// boundaries stretched on the CPU to cover the hair.
SB_INLINE float domContribution(float dz, int k, int K, int beyond) {
  return (dz < SB_DOM_D(k) || (beyond == kDomLast && k == K)) ? 1.0f : 0.0f;
}

// The thesis's counting (Kraft 2018, Listing 3): a fragment counts in its own
// layer and every layer in front of it, so layer k holds the fragments at or
// behind its start d_(k-1) (layer 1 all of them). Beyond the last layer it is
// ignored, or (kDomLast) counted in every layer, as the listing does.
SB_INLINE float domContributionPreceding(float dz, int k, int K, int beyond) {
  if (k < 1 || k > K) return 0.0f;
  if (!(dz < SB_DOM_D(K)) && beyond != kDomLast) return 0.0f;
  return dz >= SB_DOM_D(k - 1) ? 1.0f : 0.0f;
}

#ifdef SB_DOM_LAYER
// Opacity at depth z in a texel whose hair starts at z0, from K layers;
// SB_DOM_LAYER(k) (k = 1..K) is layer k's accumulated opacity. Interpolated
// within the layer holding z (0 at z0); beyond the last layer the last value.
SB_INLINE float domOpacity(float z, float z0, int K) {
  if (!(z >= z0) || K < 1) return 0.0f;
  float dz = z - z0;
  float prev = 0.0f;
  for (int k = 1; k <= K; ++k) {
    float cur = SB_DOM_LAYER(k);
    if (dz < SB_DOM_D(k)) return opacityLerp(dz, SB_DOM_D(k - 1), SB_DOM_D(k), prev, cur);
    prev = cur;
  }
  return prev;
}
#endif
#endif
