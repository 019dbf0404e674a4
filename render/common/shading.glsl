// Lighting parameters of the final shading passes (binding 1).
#include "slots.h"
#include "shading_uniforms.h"

vec3 directionToLight(vec3 p) {
  return lightPos.w > 0.5 ? normalize(lightPos.xyz - p) : normalize(lightPos.xyz);
}
