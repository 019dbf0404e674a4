// fom's parameters (its pass and lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_FOM_UNIFORMS_H
#define SB_FOM_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/fom/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(FomParams, SB_SLOT_FOM_PARAMS)
  SB_FIELD(mat4, fomViewProj)
  SB_FIELD(vec4, fomParams)  // bias (light depth units), map size, shadow alpha, 0
  SB_FIELD(vec4, fomRange)   // the hair's near and far light depth, frequencies n, 0
SB_UNIFORM_BLOCK_END(FomParams)
// clang-format on

#endif  // SB_FOM_UNIFORMS_H
