// The shaded colour of a hair fragment: the shading model chosen by --shading
// (SB_SHADING_MODEL, render/shading/shading_model.h) with the light's
// visibility from the shadow technique. Include after common/shading.glsl and <shadow>.
#ifndef SB_SHADING_MODEL
#error "hair passes need the shading's defines (HairShading::hairDefines)"
#endif
#include "techniques/kajiya_kay/kajiya_kay.glsl"
#if SB_SHADING_MODEL == 1
#include "techniques/marschner/marschner.glsl"
#elif SB_SHADING_MODEL == 2
#include "techniques/sadeghi/sadeghi.glsl"
#elif SB_SHADING_MODEL == 3
#include "slots.h"
layout(std430, binding = SB_SLOT_SHADING_TABLE) readonly buffer ShadingTable {
  float chiangTable[];  // the model's h-averaged lobes (techniques/chiang/chiang_table.cpp)
};
#include "techniques/chiang/chiang.glsl"
#ifdef SB_DUAL_SCATTERING
#include "techniques/chiang/dual.glsl"
#endif
#endif

vec3 shadeHair(vec3 worldPos, vec3 tangent, vec3 color) {
  vec3 T = normalize(tangent);
  vec3 L = directionToLight(worldPos);
  vec3 V = normalize(eyePos.xyz - worldPos);
  float visibility = shadowVisibility(worldPos);
#if SB_SHADING_MODEL == 0
  vec2 kk = kajiyaKay(T, L, V, hairMaterial.z);
  vec3 direct = (hairMaterial.x * kk.x * color + hairMaterial.y * kk.y) * lightColor.rgb;
#elif SB_SHADING_MODEL == 3 && defined(SB_DUAL_SCATTERING)
  // Dual scattering: the visibility feeds its strand count and is inside its value.
  vec3 direct = chiangDual(T, L, V, color, lobeShift, lobeWidth, lobeIntensity, visibility,
                           sceneParams.y) *
                lightColor.rgb;
  visibility = 1.0f;
#ifdef SB_FIBRE_OPACITY
  direct /= chiangOpacity(chiangX(color, lobeIntensity.z), lobeIntensity.w, SB_DUAL_OPACITY);
#endif
#elif SB_SHADING_MODEL == 3
  // The fibre alone: no diffuse term (the tracer's single scattering).
  vec3 direct = chiang(T, L, V, color, lobeShift, lobeWidth, lobeIntensity) * lightColor.rgb;
#ifdef SB_FIBRE_OPACITY
  // The strand's alpha is the fibre's opacity (chiang:opacity=fibre): its colour is what it
  // reflects over that, so the composite adds the reflection once.
  direct /= chiangOpacity(chiangX(color, lobeIntensity.z), lobeIntensity.w, SB_CHIANG_OPACITY);
#endif
#else
  // Both papers' models add a Kajiya-Kay diffuse term (the thesis, Listing 2, line 3).
  float tl = dot(T, L);
  float diffuse = sqrt(max(0.0f, 1.0f - tl * tl));
#if SB_SHADING_MODEL == 1
  // L_r = D * integral of S L_i cos(theta_i): one light, cos(theta_i) = sin(T, L).
  vec3 specular = marschner(T, L, V, color, lobeShift, lobeWidth) * diffuse;
#else
  vec3 specular = sadeghi(T, L, V, color, lobeShift, lobeWidth, lobeIntensity, sceneParams.z);
#endif
  vec3 direct = (hairMaterial.x * diffuse * color + hairMaterial.y * specular) * lightColor.rgb;
#endif
  return hairMaterial.w * color + visibility * direct;
}
