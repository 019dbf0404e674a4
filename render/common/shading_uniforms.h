// The lighting parameters of the shading passes (render/common/shading.glsl).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_COMMON_SHADING_UNIFORMS_H
#define SB_COMMON_SHADING_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(ShadingUniforms, SB_SLOT_SHADING)
  SB_FIELD(vec4, eyePos)        // xyz
  SB_FIELD(vec4, lightPos)      // w=1: point light position; w=0: direction towards the light
  SB_FIELD(vec4, lightColor)    // rgb * intensity
  SB_FIELD(vec4, hairMaterial)  // kd, ks, shininess, ambient
  SB_FIELD(vec4, meshMaterial)  // rgb, ambient
  SB_FIELD(vec4, sceneParams)   // hair alpha, shadow alpha, glint width (Sadeghi), 0
  SB_FIELD(vec4, lobeShift)     // the shading model's parameters (shading_model.h)
  SB_FIELD(vec4, lobeWidth)
  SB_FIELD(vec4, lobeIntensity)
SB_UNIFORM_BLOCK_END(ShadingUniforms)
// clang-format on

#endif  // SB_COMMON_SHADING_UNIFORMS_H
