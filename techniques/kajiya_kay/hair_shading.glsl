// The shaded colour of a hair fragment: Kajiya-Kay with the light's visibility
// from the shadow technique. Include after common/shading.glsl and <shadow>.
#include "kajiya_kay.glsl"

vec3 shadeHair(vec3 worldPos, vec3 tangent, vec3 color) {
  vec3 T = normalize(tangent);
  vec3 L = directionToLight(worldPos);
  vec3 V = normalize(eyePos.xyz - worldPos);
  vec2 kk = kajiyaKay(T, L, V, hairMaterial.z);
  float visibility = shadowVisibility(worldPos);
  vec3 direct = (hairMaterial.x * kk.x * color + hairMaterial.y * kk.y) * lightColor.rgb;
  return hairMaterial.w * color + visibility * direct;
}
