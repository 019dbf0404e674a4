// chiang in the hair shading passes (bound as <shading>, render/shading/hair_shading.glsl):
// shadingDirect is the light's term for a light of unit colour: the fibre alone, no diffuse
// term (the tracer's single scattering), or with scattering=dual Zinke et al.'s multiple
// scattering, whose value holds the light's visibility.
#include "slots.h"
#include "uniforms.h"
layout(std430, binding = SB_SLOT_CHIANG_TABLE) readonly buffer ChiangTable {
  float chiangTable[];  // the model's h-averaged lobes (chiang_table.cpp; dual_table.cpp's)
};
#include "chiang.glsl"
#include "dual.glsl"

vec3 shadingDirect(vec3 T, vec3 L, vec3 V, vec3 color, inout float visibility) {
  vec3 direct;
  vec3 neighbourhood = vec3(0.0f);
  if (chiangDualScattering != 0) {
    // Dual scattering: the visibility feeds its strand count and is inside its value.
    ChiangDualParts parts =
        chiangDualParts(T, L, V, color, chiangVariance, chiangTilt1, chiangTilt4,
                        vec2(chiangDensityF, chiangDensityB), visibility, sceneParams.y);
    direct = parts.fibre;
    neighbourhood = parts.neighbourhood;
    visibility = 1.0f;
  } else {
    direct = chiang(T, L, V, color, chiangVariance, chiangTilt1, chiangTilt4);
  }
  // The strand's alpha is the fibre's opacity (opacity=fibre): its colour is what it reflects
  // over that, so the composite adds the reflection once. The neighbourhood's back-scatter is
  // not divided: weighted by the alpha it sums to the pixel's hair coverage times it over the
  // layers, once per pixel, as dual.glsl's parts say.
  if (chiangFibreOpacity != 0)
    direct /= chiangOpacity(chiangX(color, chiangTilt4.z), chiangTilt4.w, chiangOpacityRow);
  return direct + neighbourhood;
}
