// chiang in the hair shading passes (bound as <shading>, shading/hair_shading.glsl):
// shadingDirect is the light's term for a light of unit colour: the fibre alone, no diffuse
// term (the tracer's single scattering).
#include "slots.h"
#include "uniforms.h"
layout(std430, binding = SB_SLOT_CHIANG_TABLE) readonly buffer ChiangTable {
  float chiangTable[];  // the model's h-averaged lobes (chiang_table.cpp)
};
#include "chiang.glsl"

vec3 shadingDirect(vec3 T, vec3 L, vec3 V, vec3 color) {
  return chiang(T, L, V, color, chiangVariance, chiangTilt1, chiangTilt4);
}
