// dc's lookup parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_DC_UNIFORMS_H
#define SB_DC_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/dc/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(DcParams, SB_SLOT_DC_PARAMS)
  SB_FIELD(mat4, dcViewProj)
  SB_FIELD(vec4, dcParams)  // x: bias (light depth units), y: map size, z: shadow alpha
SB_UNIFORM_BLOCK_END(DcParams)
// clang-format on

#endif  // SB_DC_UNIFORMS_H
