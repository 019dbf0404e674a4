// The hair fibre of Chiang, Bitterli, Tappan & Burley 2016, the same BSDF as the path-traced
// reference (pbr/hair_bsdf.h, its parameters and conventions), shaded the way production
// real-time hair is: the longitudinal lobes M_p evaluated analytically, the azimuthal lobes
// times their attenuation, A_p N_p, integrated over the offset h across the fibre and
// precomputed on the CPU into a table (chiang_table.cpp, from pbr/'s own Ap and Np). A pixel
// covered by a fibre sees every h in [-1, 1] with equal weight (a ribbon facing the ray, as
// the tracer's flat curves are), so the fragment's value is the h-average of f cos:
//   chiang = pi * sum over p of M_p(theta_i, theta_o tilted) * table_p(phi, |sin theta_o|, x)
// with x = sqrt(sigma_a) per channel (sigma_a from the colour by the tracer's rule,
// pbr::sigmaAFromReflectance). pi: the light's colour is the irradiance over pi (the raster's
// convention, pbr/strand_render.h). Pure math, compiled as GLSL and, through chiang.h, as C++
// with GLM so CPU tests check it against pbr/.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#include "render/common/angles.glsl"

// The table's axes: phi in [0, pi], |sin theta_o| in [0, 1], sqrt(sigma_a) in [0, xMax];
// lobes R, TT, TRT and the higher orders. Index ((p * X + x) * S + s) * PHI + phi. After the
// lobes, X more entries: the fibre's mean transmittance at normal incidence by sqrt(sigma_a)
// (pbr::meanFibreTransmittance), for chiangOpacity.
#define SB_CHIANG_PHI 64
#define SB_CHIANG_SIN 32
#define SB_CHIANG_X 32
#define SB_CHIANG_LOBES 4
// Where chiangOpacity's row starts in chiang's own table (dual scattering's has it elsewhere).
#define SB_CHIANG_OPACITY (SB_CHIANG_LOBES * SB_CHIANG_X * SB_CHIANG_SIN * SB_CHIANG_PHI)

// The table: chiangTable[], a storage buffer the includer declares (shading.glsl),
// a pointer on the CPU (chiang.h).

// log I0(x) for x >= 0, finite where I0 overflows float: the power series below 12, the
// asymptotic series above (three terms, relative error below 1e-4 there).
SB_INLINE float chiangLogI0(float x) {
  if (x > 12.0f) {
    float t = 1.0f / (8.0f * x);
    return x - 0.5f * log(6.28318530718f * x) + log(1.0f + t + 4.5f * t * t);
  }
  float q = 0.25f * x * x;
  float term = 1.0f;
  float sum = 1.0f;
  for (int k = 1; k < 40; ++k) {
    term *= q / float(k * k);
    sum += term;
    if (term < 1e-8f * sum) break;
  }
  return log(sum);
}

// d'Eon et al. 2011's longitudinal lobe of variance v, in log space (pbr::hair::Mp).
SB_INLINE float chiangMp(float cosI, float cosO, float sinI, float sinO, float v) {
  float a = cosI * cosO / v;
  float b = sinI * sinO / v;
  float logNorm = -1.0f / v - log(v) - log(1.0f - exp(-2.0f / v));
  return exp(chiangLogI0(a) - b + logNorm);
}

// Lobe p's h-averaged A_p N_p at (phi, |sin theta_o|, x), trilinear in the table.
SB_INLINE float chiangLobe(int p, float phi, float sinO, float x, float xMax) {
  float fp = clamp(phi / 3.14159265358979f, 0.0f, 1.0f) * float(SB_CHIANG_PHI - 1);
  float fs = clamp(sinO, 0.0f, 1.0f) * float(SB_CHIANG_SIN - 1);
  float fx = clamp(x / xMax, 0.0f, 1.0f) * float(SB_CHIANG_X - 1);
  int ip = min(int(fp), SB_CHIANG_PHI - 2);
  int is = min(int(fs), SB_CHIANG_SIN - 2);
  int ix = min(int(fx), SB_CHIANG_X - 2);
  float tp = fp - float(ip);
  float ts = fs - float(is);
  float tx = fx - float(ix);
  float r = 0.0f;
  for (int dx = 0; dx < 2; ++dx)
    for (int ds = 0; ds < 2; ++ds) {
      int base = ((p * SB_CHIANG_X + ix + dx) * SB_CHIANG_SIN + is + ds) * SB_CHIANG_PHI + ip;
      float w = (dx == 0 ? 1.0f - tx : tx) * (ds == 0 ? 1.0f - ts : ts);
      r += w * ((1.0f - tp) * chiangTable[base] + tp * chiangTable[base + 1]);
    }
  return r;
}

// The light a fibre of sqrt(sigma_a) x (per channel) stops as a camera ray crosses it: 1 - the
// luminance of its h-mean transmittance at normal incidence, chiangShadowAlpha's value (the
// CPU's, from which chiang:opacity=fibre scales the strands' alpha). A fragment of such a fibre
// lets the rest through, so its colour is what the fibre reflects divided by this: the
// composite then adds the reflected light once and attenuates what lies behind as the
// tracer's camera rays are (rung 2). base: where the row starts in the table bound.
SB_INLINE float chiangOpacity(vec3 x, float xMax, int base) {
  vec3 t = vec3(0.0f);
  for (int c = 0; c < 3; ++c) {
    float fx = clamp(x[c] / xMax, 0.0f, 1.0f) * float(SB_CHIANG_X - 1);
    int ix = min(int(fx), SB_CHIANG_X - 2);
    t[c] = mix(chiangTable[base + ix], chiangTable[base + ix + 1], fx - float(ix));
  }
  return max(1.0f - dot(t, vec3(0.2126f, 0.7152f, 0.0722f)), 1e-3f);
}

// sqrt(sigma_a) per channel from the colour: |ln c| / divisor (pbr::sigmaAFromReflectance),
// the colour clamped as the tracer clamps it. invDivisor: chiangTilt4.z (tilt4.z below).
SB_INLINE vec3 chiangX(vec3 color, float invDivisor) {
  return -log(clamp(color, vec3(1e-3f), vec3(1.0f))) * invDivisor;
}

// T: unit tangent (root to tip), L: unit direction to the light, V: unit direction to the eye.
// variance: M_p's variances (R, TT, TRT, higher orders); tilt1: sin, cos of alpha and 2 alpha;
// tilt4: sin, cos of 4 alpha, 1 / the colour's divisor (sqrt(sigma_a) = |ln c| / divisor) and
// the table's range of sqrt(sigma_a) (ShadingModel::shift, width, intensity; shading_model.h).
// Returns the h-averaged f cos times pi per channel.
SB_INLINE vec3 chiang(vec3 T, vec3 L, vec3 V, vec3 color, vec4 variance, vec4 tilt1, vec4 tilt4) {
  float sinI = clamp(dot(L, T), -1.0f, 1.0f);
  float sinO = clamp(dot(V, T), -1.0f, 1.0f);
  float cosI = sqrt(max(0.0f, 1.0f - sinI * sinI));
  float cosO = sqrt(max(0.0f, 1.0f - sinO * sinO));
  vec4 a = hairAngles(T, L, V);
  float phi = a.z;
  vec3 x = chiangX(color, tilt4.z);
  vec3 sum = vec3(0.0f);
  for (int p = 0; p < SB_CHIANG_LOBES; ++p) {
    // The scale tilt rotates theta_o per lobe as pbr::HairBsdf::tiltedThetaO does: R by
    // +2 alpha, TT by -alpha, TRT by -4 alpha, the higher orders not at all.
    float ss = p == 0 ? tilt1.z : (p == 1 ? -tilt1.x : (p == 2 ? -tilt4.x : 0.0f));
    float cs = p == 0 ? tilt1.w : (p == 1 ? tilt1.y : (p == 2 ? tilt4.y : 1.0f));
    float sinOp = sinO * cs + cosO * ss;
    float cosOp = abs(cosO * cs - sinO * ss);
    float v = p == 0 ? variance.x : (p == 1 ? variance.y : (p == 2 ? variance.z : variance.w));
    float m = chiangMp(cosI, cosOp, sinI, sinOp, v);
    float s = abs(sinO);
    sum += m * vec3(chiangLobe(p, phi, s, x.r, tilt4.w), chiangLobe(p, phi, s, x.g, tilt4.w),
                    chiangLobe(p, phi, s, x.b, tilt4.w));
  }
  return 3.14159265358979f * sum;
}
