// Kajiya-Kay hair shading (Kajiya & Kay 1989). Pure math, compiled as GLSL and,
// through kajiya_kay.h, as C++ with GLM so CPU tests check it.
// T: unit tangent, L: unit direction to the light, V: unit direction to the
// eye. Returns (diffuse factor, specular factor).
#ifndef SB_INLINE
#define SB_INLINE
#endif

SB_INLINE vec2 kajiyaKay(vec3 T, vec3 L, vec3 V, float shininess) {
  float tl = dot(T, L);
  float tv = dot(T, V);
  float sinTL = sqrt(max(0.0f, 1.0f - tl * tl));
  float sinTV = sqrt(max(0.0f, 1.0f - tv * tv));
  // Diffuse: Lambert integrated over the cylinder's normal plane, sin(T, L).
  // Specular: peaks on the cone of reflection, where the angle between V and
  // -T equals the angle between L and T: cos = sinTL*sinTV - tl*tv.
  float cosCone = max(0.0f, sinTL * sinTV - tl * tv);
  return vec2(sinTL, pow(cosCone, shininess));
}
