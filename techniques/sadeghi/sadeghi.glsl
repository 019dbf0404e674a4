// The artist-friendly hair shading of Sadeghi, Pritchett, Jensen & Tamstorf 2010, as the thesis
// (Kraft 2018, section 3.1 and 4.2, equations 20-24 and Listing 2) implements it:
//   f = sum over p of C_p I_p M'_p(theta_h) N'_p(phi) / cos^2(theta_d)     (23, 24)
//   M'_p = g'(beta_p; theta_h - alpha_p), g' a unit-height Gaussian        (21)
//   N'_R = cos(phi/2), N'_TT = g'(xi_TT; pi - phi),
//   N'_TRT = cos(phi/2) + I_g g'(xi_g; G_angle - phi)                      (22a-e)
// with phi the angle between light and eye projected onto the normal plane (0..pi, Listing 2).
// Colours: R takes the light's colour, TT and TRT the strand's. Pure math, compiled as GLSL and,
// through sadeghi.h, as C++ with GLM so CPU tests check it.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#include "render/common/angles.glsl"

// Unit-height Gaussian: exp(-x^2 / (2 w^2)).
SB_INLINE float sadeghiGauss(float w, float x) { return exp(-x * x / (2.0f * w * w)); }

// T: unit tangent, L: unit direction to the light, V: unit direction to the eye.
// shift = (alpha_R, alpha_TT, alpha_TRT, G_angle), width = (beta_R, beta_TT, beta_TRT, xi_TT),
// intensity = (I_R, I_TT, I_TRT, I_g), glintWidth = xi_g; angles in radians.
// cos^2(theta_d) is bounded below by 1e-2 so f stays finite looking along the fibre.
SB_INLINE vec3 sadeghi(vec3 T, vec3 L, vec3 V, vec3 color, vec4 shift, vec4 width, vec4 intensity,
                       float glintWidth) {
  vec4 a = hairAngles(T, L, V);
  float thetaH = a.x;
  float thetaD = a.y;
  float phi = a.z;
  float nR = max(cos(0.5f * phi), 0.0f);  // cos(pi/2) rounds to -4e-8 in float
  float nTT = sadeghiGauss(width.w, 3.14159265358979f - phi);
  float nTRT = nR + intensity.w * sadeghiGauss(glintWidth, shift.w - phi);
  float r = intensity.x * sadeghiGauss(width.x, thetaH - shift.x) * nR;
  float tt = intensity.y * sadeghiGauss(width.y, thetaH - shift.y) * nTT;
  float trt = intensity.z * sadeghiGauss(width.z, thetaH - shift.z) * nTRT;
  float cd = cos(thetaD);
  return (vec3(r) + color * (tt + trt)) / max(cd * cd, 1e-2f);
}
