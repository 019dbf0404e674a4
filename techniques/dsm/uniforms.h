// dsm's lookup parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_DSM_UNIFORMS_H
#define SB_DSM_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/dsm/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(DsmLookupParams, SB_SLOT_DSM_PARAMS)
  SB_FIELD(mat4, dsmViewProj)
  SB_FIELD(vec4, dsmParams)  // x: bias (light depth units), y: map size, z: shadow alpha
SB_UNIFORM_BLOCK_END(DsmLookupParams)
// clang-format on

#endif  // SB_DSM_UNIFORMS_H
