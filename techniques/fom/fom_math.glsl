// Fourier opacity maps (Jansen & Bavoil 2010): the absorption along a light
// ray, sigma(d) over the hair's normalised depth d in [0, 1], is kept as a
// truncated Fourier series
//   sigma(d) ~ a_0 / 2 + sum_k=1..n a_k cos(2 pi k d) + b_k sin(2 pi k d),
// each hair fragment at d_i adding a Dirac delta of weight w = -ln(1 - alpha)
// (so a_k += 2 w cos(2 pi k d_i), b_k += 2 w sin(2 pi k d_i), a_0 += 2 w, by
// additive blending). The optical depth in front of d is the series'
// integral from 0 to d,
//   I(d) = a_0 d / 2 + sum_k (a_k sin(2 pi k d) + b_k (1 - cos(2 pi k d))) / (2 pi k),
// and the transmittance exp(-I(d)). Truncation rings around each fragment
// (Gibbs): I(d) may dip below 0 or fall back, so exp(-I) may exceed 1 and is
// not monotone in d; the paper clamps the transmittance to [0, 1], which
// bounds it but leaves the ringing as error (and as rises along a ray).
// Stored float j: 0 is a_0, 2k - 1 is a_k, 2k is b_k. Pure math, compiled as
// GLSL and, through fom_math.h, as C++ with GLM for CPU tests.
#ifndef SB_INLINE
#define SB_INLINE
#endif

const float kFomTwoPi = 6.28318530718f;

// Absorption of one fragment of opacity alphaS (opacity 1 kept finite).
SB_INLINE float fomAbsorption(float alphaS) {
  return -log(1.0f - clamp(alphaS, 0.0f, 0.999999f));
}

// A fragment's contribution, of absorption w at depth d, to stored float j.
SB_INLINE float fomCoefficient(int j, float d, float w) {
  if (j == 0) return 2.0f * w;
  int k = (j + 1) / 2;
  float x = kFomTwoPi * float(k) * d;
  return 2.0f * w * ((j % 2 == 1) ? cos(x) : sin(x));
}

// exp(-I) clamped to [0, 1] (the paper's clamping).
SB_INLINE float fomTransmittance(float opticalDepth) {
  return clamp(exp(-opticalDepth), 0.0f, 1.0f);
}

#ifdef SB_FOM_COEFF
// I(d) from n frequencies; SB_FOM_COEFF(j) reads stored float j. In front of
// the hair (d <= 0) nothing; behind it (d >= 1) all of it.
SB_INLINE float fomOpticalDepth(float d, int n) {
  if (!(d > 0.0f)) return 0.0f;
  d = min(d, 1.0f);
  float sum = SB_FOM_COEFF(0) * d * 0.5f;
  for (int k = 1; k <= n; ++k) {
    float x = kFomTwoPi * float(k) * d;
    sum += (SB_FOM_COEFF(2 * k - 1) * sin(x) + SB_FOM_COEFF(2 * k) * (1.0f - cos(x))) /
           (kFomTwoPi * float(k));
  }
  return sum;
}
#endif
