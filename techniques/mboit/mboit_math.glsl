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
#ifndef SB_MBOIT_MATH_GLSL
#define SB_MBOIT_MATH_GLSL
#ifndef SB_INLINE
#define SB_INLINE
#endif
// Every value of the moment math is `precise` in GLSL: the reconstruction is
// so ill conditioned (a Hankel or Toeplitz solve whose smallest pivot is of
// the order of the bias, then roots next to the depth itself) that one
// rounding step more or less changes the transmittance by up to 0.1, and the
// GL and Vulkan compilers otherwise fuse and reorder different
// multiply-adds. Measured: the moment targets of both backends are bit for
// bit equal while the accumulated colour differed by up to 1.8 (moments=4)
// before this; with precise arithmetic (IEEE + - * / and sqrt, the same
// polynomial cos/sin, the drivers' shared log/exp) both backends compute the
// same bits from the same moments. C++ (mboit_math.h) defines it empty.
#ifndef SB_PRECISE
#define SB_PRECISE precise
#endif

// Largest n (2n power moments).
#define SB_MBOIT_MAX_N 4

// Every loop below runs over the constant bounds 0..SB_MBOIT_MAX_N and skips
// the indices past the pixel's n (the loop body under `if`), so that the
// compilers unroll it and every array index is a constant. Measured (the
// probe in tests/test_mboit_parity.cpp: the same moments and depths on GL,
// Vulkan and the CPU): with loops bounded by the run-time n, Mesa 22.3.6
// (llvmpipe GL and lavapipe Vulkan alike) computed wrong Newton divided
// differences, and GL also wrong polynomial coefficients, from correct
// roots: d[0] changed where no iteration writes it (T 1.0 on GL and 3.7e-7
// on Vulkan where the CPU and a double-precision evaluation of the paper's
// algorithm give 1.7e-4, on a pixel of b0 = 14.8); over 1e-3 apart in 8735
// of 17424 probes (Vulkan, 4 moments) and 10667 of 16236 (GL, 6
// trigonometric). With constant bounds the three agree
// (MboitParity.ReconstructionIsTheSameOnGlVulkanAndCpu).
// Absorbance of one fragment is capped (alpha 1 would be infinite), as the
// paper's code does: e^-10 is below 16-bit precision.
#define SB_MBOIT_MAX_ABSORBANCE 10.0f

// The paper's overestimation: the share of the fragment's own moment counted
// in front of it (0.25, their recommended value).
#define SB_MBOIT_OVERESTIMATION 0.25f

// a / b is written a * mboitRcp(b) everywhere: Mesa's GLSL compiler lowers a
// division to a reciprocal and a product, its SPIR-V path keeps the division,
// and the two round differently in the last bit (which the solve amplifies).
SB_INLINE float mboitRcp(float b) {
  SB_PRECISE float r = 1.0f / b;
  return r;
}

// Whether x is finite, from its bits: compilers may fold x == x away (GLSL
// leaves NaN undefined), an integer test they keep.
SB_INLINE bool mboitFinite(float x) {
  return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u;
}

// Pivots of the moment matrices at or below this multiple of the bias are
// what the bias itself puts there (the biased moments of fewer points than
// the system has rows give pivots of 0.2..1.4 times the bias), at the level
// of fp32 rounding noise (~1e-7 for the paper's 32-bit bias of 5e-7): the
// solve stops there and uses the leading, well-posed system (fewer points in
// the canonical representation) instead of a 0/0 that each driver's rounding
// decides differently (GL and Vulkan differed by up to 0.18 that way).
#define SB_MBOIT_PIVOT_SHARE 2.0f
// A leading coefficient of the kernel polynomial below this share of the
// largest one is 0: the depth sits on a point of the support (a single
// fragment looked up at its own depth), a root has gone to infinity with no
// mass on it, and the interpolation runs through the finite roots (the
// limit of the reconstruction) instead of dividing by 0.
#define SB_MBOIT_LEAD_SHARE 1e-6f

// Half the width of a point of the support, in warped depth (or circle
// parameter) units: the fallback below counts a point within it as at zf.
#define SB_MBOIT_POINT_WIDTH 1e-3f

// Transmittance in front of zf when all the mass is (numerically) one point
// at `at`: nothing in front before it, all of it after, the paper's
// overestimated share at it.
SB_INLINE float mboitPointTransmittance(float b0, float at, float zf, float overestimation) {
  SB_PRECISE float share = zf < at - SB_MBOIT_POINT_WIDTH
                               ? 0.0f
                               : (zf > at + SB_MBOIT_POINT_WIDTH ? 1.0f : overestimation);
  SB_PRECISE float t = clamp(exp(-b0 * share), 0.0f, 1.0f);
  return t;
}

SB_INLINE float mboitAbsorbance(float alpha) {
  SB_PRECISE float a = min(-log(clamp(1.0f - alpha, 1e-30f, 1.0f)), SB_MBOIT_MAX_ABSORBANCE);
  return a;
}

// Depth warp: view distance z to [-1, 1], logarithmic between the near and far
// distances of the hair (the paper's log depth; logNear = ln(near), invRange =
// 1 / (ln(far) - ln(near))).
SB_INLINE float mboitWarpDepth(float z, float logNear, float invRange) {
  SB_PRECISE float u = clamp((log(max(z, 1e-6f)) - logNear) * invRange, 0.0f, 1.0f);
  SB_PRECISE float w = u * 2.0f - 1.0f;
  return w;
}

// (z, z^2, z^3, z^4) and (z^5, .., z^8): what a fragment adds, times A.
SB_INLINE vec4 mboitPowersLow(float z) {
  SB_PRECISE float z2 = z * z;
  SB_PRECISE vec4 r = vec4(z, z2, z2 * z, z2 * z2);
  return r;
}
SB_INLINE vec4 mboitPowersHigh(float z) {
  SB_PRECISE float z4 = z * z * z * z;
  SB_PRECISE vec4 r = mboitPowersLow(z) * z4;
  return r;
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

// Complex polynomial coefficients (v[j] of z^j) or roots (v[0..n-1]).
struct MboitPoly {
  vec2 v[SB_MBOIT_MAX_N + 1];
};

// The n roots of the monic z^n + a_(n-1) z^(n-1) + .. + a_0 (a.v[n] = 1) by
// Durand-Kerner iteration in complex arithmetic: one method, only + - * /,
// for the real roots of the power moments' polynomial and the roots on the
// unit circle of the trigonometric ones (distinct for a positive definite
// moment matrix, which the bias guarantees).
SB_INLINE MboitPoly mboitRootsMonic(int n, MboitPoly a) {
  SB_PRECISE MboitPoly z;
  SB_PRECISE float gr = 1.0f, gi = 0.0f;  // powers of (0.4 + 0.9i): the usual distinct start values
  for (int l = 0; l <= SB_MBOIT_MAX_N; ++l) {
    z.v[l] = vec2(gr, gi);
    SB_PRECISE float t = gr * 0.4f - gi * 0.9f;
    gi = gr * 0.9f + gi * 0.4f;
    gr = t;
  }
  for (int it = 0; it < 48; ++it) {
    for (int l = 0; l < SB_MBOIT_MAX_N; ++l) {
      if (l < n) {
        // p(z_l) by Horner, monic.
        SB_PRECISE float zr = z.v[l].x, zi = z.v[l].y;
        SB_PRECISE float pr = 1.0f, pi = 0.0f;
        for (int j = SB_MBOIT_MAX_N - 1; j >= 0; --j) {
          if (j < n) {
            SB_PRECISE float t = pr * zr - pi * zi + a.v[j].x;
            pi = pr * zi + pi * zr + a.v[j].y;
            pr = t;
          }
        }
        // q = prod over the other roots of (z_l - z_m).
        SB_PRECISE float qr = 1.0f, qi = 0.0f;
        for (int m = 0; m < SB_MBOIT_MAX_N; ++m) {
          if (m < n && m != l) {
            SB_PRECISE float dr = zr - z.v[m].x, di = zi - z.v[m].y;
            SB_PRECISE float t = qr * dr - qi * di;
            qi = qr * di + qi * dr;
            qr = t;
          }
        }
        SB_PRECISE float den = max(qr * qr + qi * qi, 1e-30f);
        SB_PRECISE float invDen = mboitRcp(den);
        z.v[l] = vec2(zr - (pr * qr + pi * qi) * invDen, zi - (pi * qr - pr * qi) * invDen);
      }
    }
  }
  return z;
}

// Transmittance in front of warped depth zf for 2n power moments (n = 2, 3, 4):
// b0 the summed absorbance, low = (b1..b4), high = (b5..b8) as summed (not yet
// divided by b0). 1 where nothing was drawn.
SB_INLINE float mboitTransmittance(int n, float b0, vec4 low, vec4 high, float zf, float bias,
                                   float overestimation) {
  if (b0 < 1e-6f) return 1.0f;
  // Normalised, biased moments b[0..2n].
  SB_PRECISE float b[2 * SB_MBOIT_MAX_N + 1];
  SB_PRECISE float invB0 = mboitRcp(b0);
  b[0] = 1.0f;
  for (int k = 1; k <= 2 * SB_MBOIT_MAX_N; ++k) {
    // Both sides of ?: are evaluated: the indices stay in bounds (an
    // out-of-range vector index is undefined in GLSL and differed by driver).
    SB_PRECISE float m = k <= 4 ? low[min(k - 1, 3)] : high[max(k - 5, 0)];
    b[k] = (m * invB0) * (1.0f - bias) + mboitBiasVector(n, k) * bias;  // mix, spelled out
  }
  // Hankel system B c = (1, zf, .., zf^n), Gaussian elimination (B is positive
  // definite after biasing: no pivoting needed); a pivot at the noise level
  // ends the system there (SB_MBOIT_PIVOT_SHARE): n roots become n - 1 or fewer.
  const int N = SB_MBOIT_MAX_N + 1;
  SB_PRECISE float B[(SB_MBOIT_MAX_N + 1) * (SB_MBOIT_MAX_N + 1)];
  SB_PRECISE float c[SB_MBOIT_MAX_N + 1];
  SB_PRECISE float zp = 1.0f;
  for (int i = 0; i <= SB_MBOIT_MAX_N; ++i) {
    for (int j = 0; j <= SB_MBOIT_MAX_N; ++j) B[i * N + j] = b[i + j];
    c[i] = zp;
    zp *= zf;
  }
  SB_PRECISE float threshold = SB_MBOIT_PIVOT_SHARE * bias;
  int full = n;
  for (int i = 0; i <= SB_MBOIT_MAX_N; ++i) {
    if (i <= full && !(B[i * N + i] > threshold)) full = i - 1;
    if (i <= full) {
      SB_PRECISE float inv = mboitRcp(B[i * N + i]);
      for (int r = 1; r <= SB_MBOIT_MAX_N; ++r) {
        if (r > i && r <= n) {
          SB_PRECISE float f = B[r * N + i] * inv;
          for (int j = 0; j <= SB_MBOIT_MAX_N; ++j)
            if (j >= i && j <= n) B[r * N + j] -= f * B[i * N + j];
          c[r] -= f * c[i];
        }
      }
    }
  }
  n = full;
  if (n < 1) return mboitPointTransmittance(b0, b[1], zf, overestimation);  // one point
  for (int i = SB_MBOIT_MAX_N; i >= 0; --i) {
    if (i <= n) {
      SB_PRECISE float s = c[i];
      for (int j = 1; j <= SB_MBOIT_MAX_N; ++j)
        if (j > i && j <= n) s -= B[i * N + j] * c[j];
      c[i] = s * mboitRcp(B[i * N + i]);
    }
  }
  SB_PRECISE float cmax = 0.0f;
  for (int j = 0; j < SB_MBOIT_MAX_N; ++j)
    if (j < n) cmax = max(cmax, abs(c[j]));
  for (int j = SB_MBOIT_MAX_N; j >= 1; --j)
    if (j == n && !(abs(c[j]) > SB_MBOIT_LEAD_SHARE * cmax)) n = j - 1;
  if (n < 1) return mboitPointTransmittance(b0, b[1], zf, overestimation);
  // Roots of c_0 + c_1 z + .. + c_n z^n (real for a positive definite B).
  SB_PRECISE float lead = 1.0f;
  for (int j = 1; j <= SB_MBOIT_MAX_N; ++j)
    if (j == n) lead = c[j];
  SB_PRECISE MboitPoly a;
  SB_PRECISE float invLead = mboitRcp(lead);
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j) a.v[j] = vec2(j <= n ? c[j] * invLead : 0.0f, 0.0f);
  SB_PRECISE MboitPoly roots = mboitRootsMonic(n, a);
  // Interpolate f at x_0 = zf and the roots (Newton divided differences),
  // then expand to monomial coefficients p and take sum p_j b_j.
  SB_PRECISE float x[SB_MBOIT_MAX_N + 1], d[SB_MBOIT_MAX_N + 1];
  x[0] = zf;
  d[0] = overestimation;
  for (int l = 1; l <= SB_MBOIT_MAX_N; ++l) {
    x[l] = roots.v[l - 1].x;
    d[l] = x[l] < zf ? 1.0f : 0.0f;
  }
  for (int level = 1; level <= SB_MBOIT_MAX_N; ++level) {
    for (int l = SB_MBOIT_MAX_N; l >= 1; --l) {
      if (level <= n && l >= level && l <= n) {
        SB_PRECISE float dx = x[l] - x[l - level];
        d[l] = (d[l] - d[l - 1]) * mboitRcp(abs(dx) > 1e-7f ? dx : (dx < 0.0f ? -1e-7f : 1e-7f));
      }
    }
  }
  SB_PRECISE float p[SB_MBOIT_MAX_N + 1];
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j) p[j] = 0.0f;
  for (int j = 1; j <= SB_MBOIT_MAX_N; ++j)
    if (j == n) p[0] = d[j];
  for (int l = SB_MBOIT_MAX_N - 1; l >= 0; --l) {
    if (l < n) {
      // p = p * (z - x_l) + d_l
      for (int j = SB_MBOIT_MAX_N; j >= 1; --j)
        if (j <= n) p[j] = p[j - 1] - x[l] * p[j];
      p[0] = -x[l] * p[0] + d[l];
    }
  }
  SB_PRECISE float absorbance = 0.0f;
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j)
    if (j <= n) absorbance += p[j] * b[j];
  // Round-off can leave it a little outside [0, 1] of b0; a NaN from a
  // degenerate system counts as the overestimated own share only.
  if (!mboitFinite(absorbance)) absorbance = overestimation;
  SB_PRECISE float t = clamp(exp(-b0 * clamp(absorbance, 0.0f, 1.0f)), 0.0f, 1.0f);
  return t;
}

// ------------------------------------------------ trigonometric moments --
// The paper's trigonometric moments (its section 3.2): the warped depth z in
// [-1, 1] becomes the phase phi = (z + 1) (pi - w / 2) on the unit circle,
// leaving a wrapping zone of angle w (the paper's 0.1 pi) between the far
// and the near end, and every fragment adds A e^(i k phi), k = 1..m, to the
// m complex moments (2, 3 or 4: with b0 the paper's 5, 7 and 9 real values).
// The reconstruction solves the Toeplitz system of the moments (Cholesky,
// LDL^H) for the polynomial whose roots on the unit circle are the canonical
// representation's points, and interpolates like the power moments.

#define SB_MBOIT_POWER 0
#define SB_MBOIT_TRIG 1
#define SB_MBOIT_WRAP_ANGLE 0.31415926535897932f
#define SB_MBOIT_PI 3.14159265358979323f

// cos and sin as polynomials (Taylor to degree 12/13 after reduction to
// |r| <= pi/4, error below 1e-8), so that GL and Vulkan generate the moments
// with the same arithmetic: the drivers lower the builtins differently (as
// render/common/angles.glsl found for acos), and the moment solve
// amplifies any difference in the moments.
SB_INLINE vec2 mboitCosSin(float x) {
  SB_PRECISE float q = floor(x * 0.63661977236758134f + 0.5f);  // nearest multiple of pi/2
  SB_PRECISE float r = (x - q * 1.5703125f) - q * 4.8382679489661923e-4f;  // two-part pi/2
  SB_PRECISE float r2 = r * r;
  // Taylor coefficients 1/k! as literals (no constant division to fold).
  SB_PRECISE float s =
      r * (1.0f + r2 * (-0.16666667f + r2 * (0.0083333333f +
                                              r2 * (-1.9841270e-4f + r2 * 2.7557319e-6f))));
  SB_PRECISE float c =
      1.0f + r2 * (-0.5f + r2 * (0.041666667f +
                                 r2 * (-0.0013888889f + r2 * (2.4801587e-5f - r2 * 2.7557319e-7f))));
  int k = int(q) & 3;
  if (k == 0) return vec2(c, s);
  if (k == 1) return vec2(-s, c);
  if (k == 2) return vec2(-c, -s);
  return vec2(s, -c);
}

SB_INLINE vec2 mboitCmul(vec2 a, vec2 b) {
  SB_PRECISE vec2 r = vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
  return r;
}
SB_INLINE vec2 mboitConj(vec2 a) { return vec2(a.x, -a.y); }
SB_INLINE vec2 mboitCdiv(vec2 a, vec2 b) {
  SB_PRECISE float d = max(b.x * b.x + b.y * b.y, 1e-30f);
  SB_PRECISE vec2 r = vec2(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) * mboitRcp(d);
  return r;
}

// The phase of warped depth z: (z + 1) (pi - w / 2).
SB_INLINE float mboitTrigPhase(float z) {
  SB_PRECISE float phase = (z + 1.0f) * (SB_MBOIT_PI - 0.5f * SB_MBOIT_WRAP_ANGLE);
  return phase;
}
// (e^(i phi), e^(2 i phi)) and (e^(3 i phi), e^(4 i phi)): what a fragment adds, times A.
SB_INLINE vec4 mboitTrigLow(float z) {
  SB_PRECISE vec2 w = mboitCosSin(mboitTrigPhase(z));
  SB_PRECISE vec2 w2 = mboitCmul(w, w);
  return vec4(w.x, w.y, w2.x, w2.y);
}
SB_INLINE vec4 mboitTrigHigh(float z) {
  SB_PRECISE vec2 w = mboitCosSin(mboitTrigPhase(z));
  SB_PRECISE vec2 w2 = mboitCmul(w, w);
  SB_PRECISE vec2 w3 = mboitCmul(w2, w);
  SB_PRECISE vec2 w4 = mboitCmul(w2, w2);
  return vec4(w3.x, w3.y, w4.x, w4.y);
}

// The paper's bias for m = 2, 3, 4 trigonometric moments at 16 or 32 bits
// (towards the uniform distribution: the moments are scaled by 1 - bias).
SB_INLINE float mboitTrigBias(int m, int bits) {
  if (m == 2) return bits == 16 ? 4e-4f : 4e-7f;
  if (m == 3) return bits == 16 ? 6.5e-4f : 8e-7f;
  return bits == 16 ? 8.5e-4f : 1.5e-6f;
}

// A parameter growing monotonically with the angle of a point on the unit
// circle from 0 to 2 pi (0..8, not arc length: the paper's cheap ordering).
SB_INLINE float mboitCircleParameter(vec2 p) {
  SB_PRECISE float r = abs(p.y) - abs(p.x);
  r = p.x < 0.0f ? 2.0f - r : r;
  SB_PRECISE float q = p.y < 0.0f ? 6.0f - r : r;
  return q;
}

// The paper's wrapping zone: roots in the zone between the far end and 2 pi
// count linearly more as being in front (a ramp from 0 to 1 in parameter
// space); returns (slope, offset) of that ramp.
SB_INLINE vec2 mboitWrapRamp() {
  SB_PRECISE vec2 p = mboitCosSin(2.0f * SB_MBOIT_PI - SB_MBOIT_WRAP_ANGLE);
  SB_PRECISE float begin = mboitCircleParameter(p);
  SB_PRECISE float slope = mboitRcp(7.0f - begin);
  SB_PRECISE vec2 r = vec2(slope, 1.0f - 7.0f * slope);
  return r;
}

// Transmittance in front of warped depth zf from m = 2, 3, 4 trigonometric
// moments: low = (t1, t2), high = (t3, t4) as summed (re, im pairs, not yet
// divided by b0). 1 where nothing was drawn.
SB_INLINE float mboitTrigTransmittance(int m, float b0, vec4 low, vec4 high, float zf, float bias,
                                       float overestimation) {
  if (b0 < 1e-6f) return 1.0f;
  SB_PRECISE vec2 b[SB_MBOIT_MAX_N + 1];
  b[0] = vec2(1.0f, 0.0f);
  SB_PRECISE float scale = (1.0f - bias) * mboitRcp(b0);
  b[1] = vec2(low.x, low.y) * scale;
  b[2] = vec2(low.z, low.w) * scale;
  b[3] = vec2(high.x, high.y) * scale;
  b[4] = vec2(high.z, high.w) * scale;
  // LDL^H of the Hermitian Toeplitz matrix B_ij = b_(i-j) (i >= j), in the
  // paper's order: L_ij = (B_ij - sum_k<j L_ik conj(L_jk) D_k) / D_j.
  const int N = SB_MBOIT_MAX_N + 1;
  SB_PRECISE vec2 L[(SB_MBOIT_MAX_N + 1) * (SB_MBOIT_MAX_N + 1)];
  SB_PRECISE float D[SB_MBOIT_MAX_N + 1];
  SB_PRECISE float threshold = SB_MBOIT_PIVOT_SHARE * bias;
  int full = m;
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j) {
    if (j <= full) {
      SB_PRECISE float d = 1.0f;
      for (int k = 0; k < SB_MBOIT_MAX_N; ++k)
        if (k < j) d -= D[k] * dot(L[j * N + k], L[j * N + k]);
      if (!(d > threshold)) full = j - 1;  // noise: the leading system is what is known
      if (j <= full) {
        D[j] = d;
        for (int i = 1; i <= SB_MBOIT_MAX_N; ++i) {
          if (i > j && i <= m) {
            SB_PRECISE vec2 v = b[i - j];
            for (int k = 0; k < SB_MBOIT_MAX_N; ++k)
              if (k < j) v -= D[k] * mboitCmul(L[i * N + k], mboitConj(L[j * N + k]));
            L[i * N + j] = v * mboitRcp(d);
          }
        }
      }
    }
  }
  SB_PRECISE vec2 w = mboitCosSin(mboitTrigPhase(zf));
  m = full;
  if (m < 1)
    return mboitPointTransmittance(b0, mboitCircleParameter(b[1]), mboitCircleParameter(w),
                                   overestimation);
  // Solve B c = (1, w, .., w^m), w the point of zf on the circle.
  SB_PRECISE vec2 c[SB_MBOIT_MAX_N + 1];
  c[0] = vec2(1.0f, 0.0f);
  for (int i = 1; i <= SB_MBOIT_MAX_N; ++i) c[i] = mboitCmul(c[i - 1], w);
  for (int i = 1; i <= SB_MBOIT_MAX_N; ++i)
    if (i <= m)
      for (int k = 0; k < SB_MBOIT_MAX_N; ++k)
        if (k < i) c[i] -= mboitCmul(L[i * N + k], c[k]);
  for (int i = 0; i <= SB_MBOIT_MAX_N; ++i)
    if (i <= m) c[i] *= mboitRcp(D[i]);
  for (int i = SB_MBOIT_MAX_N - 1; i >= 0; --i)
    if (i < m)
      for (int k = 1; k <= SB_MBOIT_MAX_N; ++k)
        if (k > i && k <= m) c[i] -= mboitCmul(mboitConj(L[k * N + i]), c[k]);
  SB_PRECISE float cmax = 0.0f;
  for (int j = 0; j < SB_MBOIT_MAX_N; ++j)
    if (j < m) cmax = max(cmax, length(c[j]));
  for (int j = SB_MBOIT_MAX_N; j >= 1; --j)
    if (j == m && !(length(c[j]) > SB_MBOIT_LEAD_SHARE * cmax)) m = j - 1;
  if (m < 1)
    return mboitPointTransmittance(b0, mboitCircleParameter(b[1]), mboitCircleParameter(w),
                                   overestimation);
  // Roots of sum conj(c_j) z^j (on the unit circle).
  SB_PRECISE vec2 lead = vec2(1.0f, 0.0f);
  for (int j = 1; j <= SB_MBOIT_MAX_N; ++j)
    if (j == m) lead = mboitConj(c[j]);
  SB_PRECISE MboitPoly a;
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j)
    a.v[j] = j <= m ? mboitCdiv(mboitConj(c[j]), lead) : vec2(0.0f);
  SB_PRECISE MboitPoly roots = mboitRootsMonic(m, a);
  SB_PRECISE vec2 z[SB_MBOIT_MAX_N + 1];
  z[0] = w;
  for (int l = 1; l <= SB_MBOIT_MAX_N; ++l) z[l] = roots.v[l - 1];
  // Weights: 1 for roots in front of zf, the ramp in the wrapping zone, the
  // overestimation at zf itself.
  SB_PRECISE vec2 ramp = mboitWrapRamp();
  SB_PRECISE float ref = mboitCircleParameter(w);
  SB_PRECISE float f[SB_MBOIT_MAX_N + 1];
  f[0] = overestimation;
  for (int l = 1; l <= SB_MBOIT_MAX_N; ++l) {
    SB_PRECISE float rp = mboitCircleParameter(z[l]);
    f[l] = (rp < ref ? 1.0f : 0.0f) + clamp(rp * ramp.x + ramp.y, 0.0f, 1.0f);
  }
  // Newton divided differences through (z_l, f_l), expanded to monomial
  // coefficients p, then the absorbance Re(sum p_j b_j).
  SB_PRECISE vec2 d[SB_MBOIT_MAX_N + 1];
  for (int l = 0; l <= SB_MBOIT_MAX_N; ++l) d[l] = vec2(f[l], 0.0f);
  for (int level = 1; level <= SB_MBOIT_MAX_N; ++level)
    for (int l = SB_MBOIT_MAX_N; l >= 1; --l)
      if (level <= m && l >= level && l <= m)
        d[l] = mboitCdiv(d[l] - d[l - 1], z[l] - z[l - level]);
  SB_PRECISE vec2 p[SB_MBOIT_MAX_N + 1];
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j) p[j] = vec2(0.0f);
  for (int j = 1; j <= SB_MBOIT_MAX_N; ++j)
    if (j == m) p[0] = d[j];
  for (int l = SB_MBOIT_MAX_N - 1; l >= 0; --l) {
    if (l < m) {
      for (int j = SB_MBOIT_MAX_N; j >= 1; --j)
        if (j <= m) p[j] = p[j - 1] - mboitCmul(z[l], p[j]);
      p[0] = d[l] - mboitCmul(z[l], p[0]);
    }
  }
  SB_PRECISE float absorbance = 0.0f;
  for (int j = 0; j <= SB_MBOIT_MAX_N; ++j)
    if (j <= m) absorbance += mboitCmul(p[j], b[j]).x;
  if (!mboitFinite(absorbance)) absorbance = overestimation;
  SB_PRECISE float t = clamp(exp(-b0 * clamp(absorbance, 0.0f, 1.0f)), 0.0f, 1.0f);
  return t;
}

// What one fragment at warped depth z adds to the moment targets, times its
// absorbance: power (z..z^4), (z^5..z^8) or trigonometric (t1, t2), (t3, t4).
SB_INLINE vec4 mboitMomentsLow(int kind, float z) {
  return kind == SB_MBOIT_TRIG ? mboitTrigLow(z) : mboitPowersLow(z);
}
SB_INLINE vec4 mboitMomentsHigh(int kind, float z) {
  return kind == SB_MBOIT_TRIG ? mboitTrigHigh(z) : mboitPowersHigh(z);
}

// The paper's bias for `moments` real values beyond b0 (4, 6, 8) of a kind.
SB_INLINE float mboitKindBias(int kind, int moments, int bits) {
  return kind == SB_MBOIT_TRIG ? mboitTrigBias(moments / 2, bits) : mboitBias(moments / 2, bits);
}

// The transmittance in front of zf for either kind (moments: 4, 6 or 8 real
// values beyond b0).
SB_INLINE float mboitTransmittanceOf(int kind, int moments, float b0, vec4 low, vec4 high, float zf,
                                     float bias, float overestimation) {
  if (kind == SB_MBOIT_TRIG)
    return mboitTrigTransmittance(moments / 2, b0, low, high, zf, bias, overestimation);
  return mboitTransmittance(moments / 2, b0, low, high, zf, bias, overestimation);
}

// The composite (the paper's eq. 13): the transmittance-weighted average of
// the fragments' colours times the total coverage 1 - e^-b0. accum = sum of
// (c a T(z), a T(z)); returns vec4(hair, T) for C = hair + T * C_dst.
SB_INLINE vec4 mboitResolve(vec4 accum, float b0) {
  SB_PRECISE float t = exp(-max(b0, 0.0f));
  SB_PRECISE vec3 avg = vec3(accum.x, accum.y, accum.z) * mboitRcp(max(accum.w, 1e-20f));
  if (!(accum.w > 0.0f)) avg = vec3(0.0f);
  avg = clamp(avg, vec3(0.0f), vec3(1.0f));
  SB_PRECISE vec4 r = vec4(avg * (1.0f - t), t);
  return r;
}
#endif  // SB_MBOIT_MATH_GLSL
