// Moment-based order-independent transparency (Muenstermann, Krumpen, Klein &
// Peters 2018, "Moment-Based Order-Independent Transparency", PACMCGIT 1(1)):
// moment generation and the reconstruction of the transmittance in front of a
// depth with the paper's bias. Pure math, compiled as GLSL and, through
// mboit_math.h, as C++ with GLM for tests (C-style arrays read the same in
// both languages).
//
// Generation (additive): every fragment of absorbance A = -ln(1 - alpha) adds
// A to b0 and A z^k to b_k (k = 1..2n), z the warped depth in [-1, 1].
// Reconstruction at depth zf (the paper's Algorithm 2, written for any n as in
// Peters et al.'s moment shadow mapping): normalise b_k / b0, bias towards the
// paper's vector (b = (1 - beta) b + beta b*), solve the Hankel system
// B c = (1, zf, .., zf^n), take the n roots of sum c_j z^j, interpolate
// f(zf) = overestimation, f(z_l) = [z_l < zf] with a polynomial p of degree n
// and read the absorbance in front as b0 * sum p_j b_j. The roots are found by
// Durand-Kerner iteration in complex arithmetic (they are real and distinct
// for a positive definite B, which the bias guarantees), one method for n = 2,
// 3 and 4 instead of three closed forms.
#ifndef SB_INLINE
#define SB_INLINE
#endif

// Largest n (2n power moments).
#define SB_MBOIT_MAX_N 4
// Absorbance of one fragment is capped (alpha 1 would be infinite), as the
// paper's code does: e^-10 is below 16-bit precision.
#define SB_MBOIT_MAX_ABSORBANCE 10.0f

// The paper's overestimation: the share of the fragment's own moment counted
// in front of it (0.25, their recommended value).
#define SB_MBOIT_OVERESTIMATION 0.25f

SB_INLINE float mboitAbsorbance(float alpha) {
  return min(-log(clamp(1.0f - alpha, 1e-30f, 1.0f)), SB_MBOIT_MAX_ABSORBANCE);
}

// Depth warp: view distance z to [-1, 1], logarithmic between the near and far
// distances of the hair (the paper's log depth; logNear = ln(near), invRange =
// 1 / (ln(far) - ln(near))).
SB_INLINE float mboitWarpDepth(float z, float logNear, float invRange) {
  return clamp((log(max(z, 1e-6f)) - logNear) * invRange, 0.0f, 1.0f) * 2.0f - 1.0f;
}

// (z, z^2, z^3, z^4) and (z^5, .., z^8): what a fragment adds, times A.
SB_INLINE vec4 mboitPowersLow(float z) {
  float z2 = z * z;
  return vec4(z, z2, z2 * z, z2 * z2);
}
SB_INLINE vec4 mboitPowersHigh(float z) {
  float z4 = z * z * z * z;
  return mboitPowersLow(z) * z4;
}

// The paper's bias for 2n power moments at 16 or 32 bits (its Table / code).
SB_INLINE float mboitBias(int n, int bits) {
  if (n == 2) return bits == 16 ? 6e-5f : 5e-7f;
  if (n == 3) return bits == 16 ? 6e-4f : 5e-6f;
  return bits == 16 ? 2.5e-3f : 5e-5f;
}

// Moment k (1..2n) of the bias vector b* the moments are pulled towards.
SB_INLINE float mboitBiasVector(int n, int k) {
  if ((k % 2) == 1) return 0.0f;  // odd moments: 0
  if (n == 2) return 0.375f;
  if (n == 3) return k == 2 ? 0.48f : (k == 4 ? 0.451f : 0.45f);
  if (k == 2) return 0.75f;
  if (k == 4) return 0.67666666666666664f;
  if (k == 6) return 0.63f;
  return 0.60030303030303034f;
}

// Transmittance in front of warped depth zf for 2n power moments (n = 2, 3, 4):
// b0 the summed absorbance, low = (b1..b4), high = (b5..b8) as summed (not yet
// divided by b0). 1 where nothing was drawn.
SB_INLINE float mboitTransmittance(int n, float b0, vec4 low, vec4 high, float zf, float bias,
                                   float overestimation) {
  if (b0 < 1e-6f) return 1.0f;
  // Normalised, biased moments b[0..2n].
  float b[2 * SB_MBOIT_MAX_N + 1];
  b[0] = 1.0f;
  for (int k = 1; k <= 2 * SB_MBOIT_MAX_N; ++k) {
    float m = k <= 4 ? low[k - 1] : high[k - 5];
    b[k] = mix(m / b0, mboitBiasVector(n, k), bias);
  }
  // Hankel system B c = (1, zf, .., zf^n), Gaussian elimination (B is positive
  // definite after biasing: no pivoting needed).
  const int N = SB_MBOIT_MAX_N + 1;
  float B[(SB_MBOIT_MAX_N + 1) * (SB_MBOIT_MAX_N + 1)];
  float c[SB_MBOIT_MAX_N + 1];
  float zp = 1.0f;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) B[i * N + j] = b[i + j];
    c[i] = zp;
    zp *= zf;
  }
  for (int i = 0; i <= n; ++i) {
    float inv = 1.0f / B[i * N + i];
    for (int r = i + 1; r <= n; ++r) {
      float f = B[r * N + i] * inv;
      for (int j = i; j <= n; ++j) B[r * N + j] -= f * B[i * N + j];
      c[r] -= f * c[i];
    }
  }
  for (int i = n; i >= 0; --i) {
    float s = c[i];
    for (int j = i + 1; j <= n; ++j) s -= B[i * N + j] * c[j];
    c[i] = s / B[i * N + i];
  }
  // Roots of c_0 + c_1 z + .. + c_n z^n (monic after dividing by c_n).
  float re[SB_MBOIT_MAX_N], im[SB_MBOIT_MAX_N];
  float gr = 1.0f, gi = 0.0f;  // powers of (0.4 + 0.9i): the usual distinct start values
  for (int l = 0; l < n; ++l) {
    re[l] = gr;
    im[l] = gi;
    float t = gr * 0.4f - gi * 0.9f;
    gi = gr * 0.9f + gi * 0.4f;
    gr = t;
  }
  float invLead = 1.0f / c[n];
  for (int it = 0; it < 48; ++it) {
    for (int l = 0; l < n; ++l) {
      // p(z) by Horner, monic.
      float pr = 1.0f, pi = 0.0f;
      for (int j = n - 1; j >= 0; --j) {
        float t = pr * re[l] - pi * im[l] + c[j] * invLead;
        pi = pr * im[l] + pi * re[l];
        pr = t;
      }
      // q = prod over the other roots of (z_l - z_m).
      float qr = 1.0f, qi = 0.0f;
      for (int m = 0; m < n; ++m) {
        if (m == l) continue;
        float dr = re[l] - re[m], di = im[l] - im[m];
        float t = qr * dr - qi * di;
        qi = qr * di + qi * dr;
        qr = t;
      }
      float den = max(qr * qr + qi * qi, 1e-30f);
      re[l] -= (pr * qr + pi * qi) / den;
      im[l] -= (pi * qr - pr * qi) / den;
    }
  }
  // Interpolate f at x_0 = zf and the roots (Newton divided differences),
  // then expand to monomial coefficients p and take sum p_j b_j.
  float x[SB_MBOIT_MAX_N + 1], d[SB_MBOIT_MAX_N + 1];
  x[0] = zf;
  d[0] = overestimation;
  for (int l = 1; l <= n; ++l) {
    x[l] = re[l - 1];
    d[l] = x[l] < zf ? 1.0f : 0.0f;
  }
  for (int level = 1; level <= n; ++level)
    for (int l = n; l >= level; --l) {
      float dx = x[l] - x[l - level];
      d[l] = (d[l] - d[l - 1]) / (abs(dx) > 1e-7f ? dx : (dx < 0.0f ? -1e-7f : 1e-7f));
    }
  float p[SB_MBOIT_MAX_N + 1];
  for (int j = 0; j <= n; ++j) p[j] = 0.0f;
  p[0] = d[n];
  for (int l = n - 1; l >= 0; --l) {
    // p = p * (z - x_l) + d_l
    for (int j = n; j >= 1; --j) p[j] = p[j - 1] - x[l] * p[j];
    p[0] = -x[l] * p[0] + d[l];
  }
  float absorbance = 0.0f;
  for (int j = 0; j <= n; ++j) absorbance += p[j] * b[j];
  // Round-off can leave it a little outside [0, 1] of b0; a NaN from a
  // degenerate system counts as the overestimated own share only.
  if (!(absorbance == absorbance)) absorbance = overestimation;
  return clamp(exp(-b0 * clamp(absorbance, 0.0f, 1.0f)), 0.0f, 1.0f);
}

// The composite (the paper's eq. 13): the transmittance-weighted average of
// the fragments' colours times the total coverage 1 - e^-b0. accum = sum of
// (c a T(z), a T(z)); returns vec4(hair, T) for C = hair + T * C_dst.
SB_INLINE vec4 mboitResolve(vec4 accum, float b0) {
  float t = exp(-max(b0, 0.0f));
  vec3 avg = vec3(accum.x, accum.y, accum.z) / max(accum.w, 1e-20f);
  if (!(accum.w > 0.0f)) avg = vec3(0.0f);
  avg = clamp(avg, vec3(0.0f), vec3(1.0f));
  return vec4(avg * (1.0f - t), t);
}
