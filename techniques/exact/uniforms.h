// exact's parameters (its light passes, through exact.glsl, and its lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_EXACT_UNIFORMS_H
#define SB_EXACT_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(ExactShadowParams, SB_SLOT_EXACT_PARAMS)
  SB_FIELD(mat4, exactViewProj)
  SB_FIELD(vec4, exactParams)  // x: bias (light depth units), y: map size, z: shadow alpha,
                               // w: 1 = opaque map (the light passes)
SB_UNIFORM_BLOCK_END(ExactShadowParams)
// clang-format on

#endif  // SB_EXACT_UNIFORMS_H
