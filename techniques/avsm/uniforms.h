// avsm's lookup parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_AVSM_UNIFORMS_H
#define SB_AVSM_UNIFORMS_H

#include "techniques/avsm/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(AvsmLookupParams, SB_SLOT_AVSM_PARAMS)
  SB_FIELD(mat4, avsmViewProj)
  SB_FIELD(vec4, avsmParams)  // x: bias (light depth units), y: map size, z: shadow alpha
SB_UNIFORM_BLOCK_END(AvsmLookupParams)
// clang-format on

#endif  // SB_AVSM_UNIFORMS_H
