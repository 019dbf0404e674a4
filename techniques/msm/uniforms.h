// msm's parameters (its pass and lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_MSM_UNIFORMS_H
#define SB_MSM_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/msm/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(MsmParams, SB_SLOT_MSM_PARAMS)
  SB_FIELD(mat4, msmViewProj)
  SB_FIELD(vec4, msmParams)  // lookup bias (light depth units), map size, shadow alpha, moment bias
  SB_FIELD(vec4, msmRange)   // the hair's near and far light depth, overestimation, 0
  SB_FIELD(ivec4, msmN)      // x: real moments beyond b0 (4, 6, 8), y: kind (0 power, 1 trig)
SB_UNIFORM_BLOCK_END(MsmParams)
// clang-format on

#endif  // SB_MSM_UNIFORMS_H
