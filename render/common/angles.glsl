// acos and asin as one polynomial (Abramowitz & Stegun 4.4.46, |error| <= 2e-8), so that GL and
// Vulkan compute the hair shading models' angles with the same arithmetic: the drivers' own
// acos lowerings differ by more than the baselines' tolerance once a narrow lobe amplifies them.
// Compiled as GLSL and as C++ (through the models' headers).
#ifndef SB_ANGLES_GLSL
#define SB_ANGLES_GLSL
#ifndef SB_INLINE
#define SB_INLINE
#endif

SB_INLINE float sbAcos(float x) {
  float a = min(abs(x), 1.0f);
  float p = -0.0012624911f;
  p = p * a + 0.0066700901f;
  p = p * a - 0.0170881256f;
  p = p * a + 0.0308918810f;
  p = p * a - 0.0501743046f;
  p = p * a + 0.0889789874f;
  p = p * a - 0.2145988016f;
  p = p * a + 1.5707963050f;
  float r = sqrt(1.0f - a) * p;
  return x < 0.0f ? 3.14159265358979f - r : r;
}

SB_INLINE float sbAsin(float x) { return 1.57079632679490f - sbAcos(x); }

// The angles of Marschner et al.'s hair models. T: unit tangent (root to tip), L, V: unit
// directions to the light and the eye. Returns (theta_h, theta_d, phi, sin theta_r): theta_i,
// theta_r are the angles to the normal plane, theta_h their mean, theta_d half their
// difference, phi the azimuth between L and V projected onto the normal plane (0..pi).
SB_INLINE vec4 hairAngles(vec3 T, vec3 L, vec3 V) {
  float sinI = clamp(dot(L, T), -1.0f, 1.0f);
  float sinR = clamp(dot(V, T), -1.0f, 1.0f);
  float thetaI = sbAsin(sinI);
  float thetaR = sbAsin(sinR);
  vec3 lp = L - sinI * T;
  vec3 vp = V - sinR * T;
  float lpl = length(lp);
  float vpl = length(vp);
  float cosPhi = lpl > 1e-6f && vpl > 1e-6f ? clamp(dot(lp, vp) / (lpl * vpl), -1.0f, 1.0f) : 1.0f;
  return vec4(0.5f * (thetaI + thetaR), 0.5f * (thetaR - thetaI), sbAcos(cosPhi), sinR);
}
#endif
