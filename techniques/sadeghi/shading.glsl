// sadeghi in the hair shading passes (bound as <shading>, render/shading/hair_shading.glsl):
// shadingDirect is the light's term for a light of unit colour; the light's visibility
// multiplies it (hair_shading.glsl), left as it is.
#include "uniforms.h"
#include "sadeghi.glsl"

vec3 shadingDirect(vec3 T, vec3 L, vec3 V, vec3 color, inout float visibility) {
  // A Kajiya-Kay diffuse term beside the specular sum (the thesis, Listing 2, line 3).
  float tl = dot(T, L);
  float diffuse = sqrt(max(0.0f, 1.0f - tl * tl));
  vec3 specular = sadeghi(T, L, V, color, vec4(sadeghiAlpha.xyz, sadeghiGlintAngle),
                          vec4(sadeghiBeta.xyz, sadeghiTtWidth), sadeghiIntensity,
                          sadeghiGlintWidth);
  return sadeghiDiffuse * diffuse * color + sadeghiSpecular * specular;
}
