// The shaded colour of a hair fragment: the shading model chosen by --shading, its folder's
// shading.glsl bound as <shading> (HairShading::hairDefines), with the light's visibility from
// the shadow technique. Include after common/shading.glsl and <shadow>.
#include <shading>

vec3 shadeHair(vec3 worldPos, vec3 tangent, vec3 color) {
  vec3 T = normalize(tangent);
  vec3 L = directionToLight(worldPos);
  vec3 V = normalize(eyePos.xyz - worldPos);
  float visibility = shadowVisibility(worldPos);
  // A model whose value holds the visibility (multiple scattering fed by it) sets it to 1.
  vec3 direct = shadingDirect(T, L, V, color, visibility) * lightColor.rgb;
  return sceneParams.z * color + visibility * direct;
}
