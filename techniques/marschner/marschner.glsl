// Marschner, Jensen, Cammarano, Worley & Hanrahan 2003, "Light scattering from human hair
// fibers": S = sum over p in {R, TT, TRT} of M_p(theta_h) N_p(phi) / cos^2(theta_d).
// Pure math, compiled as GLSL and, through marschner.h, as C++ with GLM so CPU tests check it.
//
// Angles as in the paper: theta_i, theta_r are the light's and the eye's angles to the normal
// plane (positive towards the tip, the tangent's direction), phi the azimuth between them;
// theta_h = (theta_i + theta_r) / 2, theta_d = (theta_r - theta_i) / 2.
//   M_p: unit-area Gaussians of width beta_p around alpha_p (the cuticle tilt).
//   N_p: the paper's azimuthal terms: for each p the roots gamma_i of phi(p, gamma_i) = phi
//        (the cubic approximation of section 4.2), each weighted by the attenuation
//        A(p, h) = (1-F)^2 F'^(p-1) T^p (F with the Bravais indices eta', eta'') over
//        |2 dphi/dh|. The TRT caustic (dphi/dh = 0) is bounded by a floor on |dphi/dh|
//        (`caustic`) instead of the paper's Gaussian glint fade: a simplification, stated.
// Absorption per channel from the strand colour: sigma_a = -ln(colour) / 4, so light crossing
// the fibre through its centre at normal incidence (T = exp(-2 sigma_a (1 + cos 2 gamma_t)) =
// exp(-4 sigma_a)) leaves with the strand's colour.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#include "render/common/angles.glsl"

#define SB_PI 3.14159265358979f

// Unit-area Gaussian: exp(-x^2 / (2 w^2)) / (w sqrt(2 pi)).
SB_INLINE float marschnerGauss(float w, float x) {
  return exp(-x * x / (2.0f * w * w)) / (w * 2.50662827463f);
}

// Fresnel reflectance for an interface of relative index eta at incidence gamma, with the
// perpendicular polarization taken at etaPerp and the parallel at etaPar (the paper's
// F(eta', eta'', gamma)); 1 under total internal reflection.
SB_INLINE float marschnerFresnel(float etaPerp, float etaPar, float gamma) {
  float c = abs(cos(gamma));
  float s = sin(gamma);
  float sPerp = s / etaPerp;
  float sPar = s / etaPar;
  if (sPerp * sPerp >= 1.0f || sPar * sPar >= 1.0f) return 1.0f;
  float cPerp = sqrt(1.0f - sPerp * sPerp);
  float cPar = sqrt(1.0f - sPar * sPar);
  float rs = (c - etaPerp * cPerp) / (c + etaPerp * cPerp);
  float rp = (etaPar * c - cPar) / (etaPar * c + cPar);
  return clamp(0.5f * (rs * rs + rp * rp), 0.0f, 1.0f);
}

SB_INLINE float marschnerCbrt(float x) { return x < 0.0f ? -pow(-x, 1.0f / 3.0f) : pow(x, 1.0f / 3.0f); }

// Azimuth wrapped into [-pi, pi].
SB_INLINE float marschnerWrap(float a) {
  return a - 2.0f * SB_PI * floor((a + SB_PI) / (2.0f * SB_PI));
}

// N_p(phi) for path p (0, 1, 2), per colour channel. etaP: eta' (theta_d); etaPP: eta''.
// sigma: absorption per channel already divided by cos(theta_t) (the paper's sigma_a').
SB_INLINE vec3 marschnerN(int p, float phi, float etaP, float etaPP, vec3 sigma, float caustic) {
  float pf = float(p);
  float c = sbAsin(clamp(1.0f / etaP, -1.0f, 1.0f));
  // phi(p, g) ~ (6pc/pi - 2) g - (8pc/pi^3) g^3 + p pi  (section 4.2); solve = phi (mod 2 pi).
  float a3 = -8.0f * pf * c / (SB_PI * SB_PI * SB_PI);
  float a1 = 6.0f * pf * c / SB_PI - 2.0f;
  float target = marschnerWrap(phi - pf * SB_PI);  // a3 g^3 + a1 g = target
  float roots[3];
  int count = 0;
  if (p == 0) {
    roots[0] = -target / 2.0f;
    count = 1;
  } else {
    // g^3 + P g + Q = 0
    float P = a1 / a3;
    float Q = -target / a3;
    float disc = Q * Q / 4.0f + P * P * P / 27.0f;
    if (disc > 0.0f) {
      float sq = sqrt(disc);
      roots[0] = marschnerCbrt(-Q / 2.0f + sq) + marschnerCbrt(-Q / 2.0f - sq);
      count = 1;
    } else {
      float m = 2.0f * sqrt(-P / 3.0f);
      float t = sbAcos(clamp(3.0f * Q / (P * m), -1.0f, 1.0f)) / 3.0f;
      for (int k = 0; k < 3; ++k) roots[k] = m * cos(t - 2.0f * SB_PI * float(k) / 3.0f);
      count = 3;
    }
  }
  vec3 sum = vec3(0.0f);
  for (int k = 0; k < count; ++k) {
    float g = roots[k];
    if (abs(g) > SB_PI / 2.0f) continue;
    float h = sin(g);
    float gt = sbAsin(clamp(h / etaP, -1.0f, 1.0f));
    // dphi/dh = (dphi/dg) / (dh/dg)
    float dphidh = (a1 + 3.0f * a3 * g * g) / max(cos(g), 1e-4f);
    float denom = max(abs(2.0f * dphidh), 2.0f * caustic);
    float f = marschnerFresnel(etaP, etaPP, g);
    vec3 att;
    if (p == 0) {
      att = vec3(f);
    } else {
      float fi = marschnerFresnel(1.0f / etaP, 1.0f / etaPP, gt);
      vec3 T = exp(-2.0f * sigma * (1.0f + cos(2.0f * gt)));
      vec3 Tp = p == 1 ? T : T * T;
      att = (1.0f - f) * (1.0f - f) * (p == 1 ? 1.0f : fi) * Tp;
    }
    sum += att / denom;
  }
  return sum;
}

// The scattering function S(omega_i, omega_r) per channel. T: unit tangent (root to tip), L:
// unit direction to the light, V: unit direction to the eye. shift = (alpha_R, alpha_TT,
// alpha_TRT, eta), width = (beta_R, beta_TT, beta_TRT, caustic floor), radians.
// cos^2(theta_d) is bounded below by 1e-2 so S stays finite looking along the fibre.
SB_INLINE vec3 marschner(vec3 T, vec3 L, vec3 V, vec3 color, vec4 shift, vec4 width) {
  vec4 a = hairAngles(T, L, V);
  float thetaH = a.x;
  float thetaD = a.y;
  float phi = a.z;  // N is symmetric in phi for a round fibre
  float sinR = a.w;
  float eta = shift.w;
  float sd = sin(thetaD);
  float cd = max(cos(thetaD), 1e-3f);
  float root = sqrt(max(eta * eta - sd * sd, 1e-6f));
  float etaP = root / cd;             // Bravais index, perpendicular
  float etaPP = eta * eta * cd / root;  // Bravais index, parallel
  // sigma_a' = sigma_a / cos(theta_t), theta_t the refracted longitudinal angle.
  float st = sinR / eta;
  float ct = sqrt(max(1.0f - st * st, 1e-6f));
  vec3 sigma = -log(clamp(color, vec3(0.01f), vec3(1.0f))) / 4.0f / ct;
  float caustic = width.w;
  vec3 s = marschnerGauss(width.x, thetaH - shift.x) * marschnerN(0, phi, etaP, etaPP, sigma, caustic) +
           marschnerGauss(width.y, thetaH - shift.y) * marschnerN(1, phi, etaP, etaPP, sigma, caustic) +
           marschnerGauss(width.z, thetaH - shift.z) * marschnerN(2, phi, etaP, etaPP, sigma, caustic);
  return s / max(cd * cd, 1e-2f);
}
