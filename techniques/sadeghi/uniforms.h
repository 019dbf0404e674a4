// sadeghi's parameters in the hair shading passes (its shading.glsl); angles in radians.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_SADEGHI_UNIFORMS_H
#define SB_SADEGHI_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(SadeghiParams, SB_SLOT_SHADING_MODEL)
  SB_FIELD(vec4, sadeghiAlpha)        // the lobes' shifts alpha_R, alpha_TT, alpha_TRT, 0
  SB_FIELD(vec4, sadeghiBeta)         // the lobes' widths beta_R, beta_TT, beta_TRT, 0
  SB_FIELD(vec4, sadeghiIntensity)    // I_R, I_TT, I_TRT, the glints' I_g
  SB_FIELD(float, sadeghiDiffuse)     // weight of the Kajiya-Kay diffuse term
  SB_FIELD(float, sadeghiSpecular)    // weight of the specular sum
  SB_FIELD(float, sadeghiGlintAngle)  // the glints' half angle G_angle
  SB_FIELD(float, sadeghiTtWidth)     // TT's azimuthal width xi_TT
  SB_FIELD(float, sadeghiGlintWidth)  // the glints' azimuthal width xi_g
  SB_FIELD(float, sadeghiUnused0)     // std140 rounds the block to 16 bytes
  SB_FIELD(float, sadeghiUnused1)
  SB_FIELD(float, sadeghiUnused2)
SB_UNIFORM_BLOCK_END(SadeghiParams)
// clang-format on

#endif  // SB_SADEGHI_UNIFORMS_H
