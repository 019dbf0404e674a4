// The parameters of both hair passes of mboit.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_MBOIT_UNIFORMS_H
#define SB_MBOIT_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/mboit/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(MboitParams, SB_SLOT_MBOIT_PARAMS)
  SB_FIELD(vec4, mboitWarp)  // ln(near), 1 / (ln(far) - ln(near)), bias, overestimation
  SB_FIELD(ivec4, mboitN)    // x: n (2n real moments beyond b0), y: bits, z: kind (0 power, 1 trig)
SB_UNIFORM_BLOCK_END(MboitParams)
// clang-format on

#endif  // SB_MBOIT_UNIFORMS_H
