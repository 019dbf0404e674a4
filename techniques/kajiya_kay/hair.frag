// Opaque hair with Kajiya-Kay shading; the shadow technique supplies the
// light's visibility through shadowVisibility() (bound as <shadow>).
#include "../common/shading.glsl"
#include "kajiya_kay.glsl"
#include <shadow>

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 T = normalize(vTangent);
  vec3 L = directionToLight(vWorldPos);
  vec3 V = normalize(eyePos.xyz - vWorldPos);
  vec2 kk = kajiyaKay(T, L, V, hairMaterial.z);
  float visibility = shadowVisibility(vWorldPos);
  vec3 direct = (hairMaterial.x * kk.x * vColor.rgb + hairMaterial.y * kk.y) * lightColor.rgb;
  outColor = vec4(hairMaterial.w * vColor.rgb + visibility * direct, 1.0);
}
