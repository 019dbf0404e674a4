// The size of peel_advance.comp's pass (peel and exact).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_COMMON_PEEL_UNIFORMS_H
#define SB_COMMON_PEEL_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(PeelSize, SB_SLOT_PEEL_ADVANCE_SIZE)
  SB_FIELD(uvec4, peelSize)  // x: pixel count
SB_UNIFORM_BLOCK_END(PeelSize)
// clang-format on

#endif  // SB_COMMON_PEEL_UNIFORMS_H
