// Lighting parameters of the final shading passes (binding 1).
#include "slots.h"
layout(std140, binding = SB_SLOT_SHADING) uniform Shading {
  vec4 eyePos;      // xyz
  vec4 lightPos;    // w=1: point light position; w=0: direction towards the light
  vec4 lightColor;  // rgb * intensity
  vec4 hairMaterial;  // kd, ks, shininess, ambient
  vec4 meshMaterial;  // rgb, ambient
  vec4 sceneParams;   // hair alpha, shadow alpha, glint width (Sadeghi), 0
  vec4 lobeShift;     // the shading model's parameters (techniques/common/shading_model.h)
  vec4 lobeWidth;
  vec4 lobeIntensity;
};

vec3 directionToLight(vec3 p) {
  return lightPos.w > 0.5 ? normalize(lightPos.xyz - p) : normalize(lightPos.xyz);
}
