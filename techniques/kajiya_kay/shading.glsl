// kajiya-kay in the hair shading passes (bound as <shading>, render/shading/hair_shading.glsl):
// shadingDirect is the light's term for a light of unit colour; the light's visibility
// multiplies it (hair_shading.glsl), left as it is.
#include "uniforms.h"
#include "kajiya_kay.glsl"

vec3 shadingDirect(vec3 T, vec3 L, vec3 V, vec3 color, inout float visibility) {
  vec2 kk = kajiyaKay(T, L, V, kajiyaKayShininess);
  return kajiyaKayDiffuse * kk.x * color + kajiyaKaySpecular * kk.y;
}
