// marschner's parameters in the hair shading passes (its shading.glsl); angles in radians.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_MARSCHNER_UNIFORMS_H
#define SB_MARSCHNER_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(MarschnerParams, SB_SLOT_SHADING_MODEL)
  SB_FIELD(vec4, marschnerAlpha)     // the lobes' shifts alpha_R, alpha_TT, alpha_TRT, 0
  SB_FIELD(vec4, marschnerBeta)      // the lobes' widths beta_R, beta_TT, beta_TRT, 0
  SB_FIELD(float, marschnerDiffuse)  // weight of the Kajiya-Kay diffuse term
  SB_FIELD(float, marschnerSpecular) // weight of the scattering function
  SB_FIELD(float, marschnerEta)      // the fibre's index of refraction
  SB_FIELD(float, marschnerCaustic)  // floor on |dphi/dh| (marschner.glsl)
SB_UNIFORM_BLOCK_END(MarschnerParams)
// clang-format on

#endif  // SB_MARSCHNER_UNIFORMS_H
