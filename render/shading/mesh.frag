// The opaque mesh: Lambert diffuse, shadowed by the same shadow technique.
#include "../common/shading.glsl"
#include <shadow>

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vNormal;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 N = normalize(vNormal);
  vec3 L = directionToLight(vWorldPos);
  vec3 V = normalize(eyePos.xyz - vWorldPos);
  if (dot(N, V) < 0.0) N = -N;  // two-sided
  float diffuse = max(dot(N, L), 0.0);
  float visibility = shadowVisibility(vWorldPos);
  vec3 albedo = meshMaterial.rgb;
  outColor = vec4(albedo * (meshMaterial.w + visibility * diffuse * lightColor.rgb), 1.0);
}
