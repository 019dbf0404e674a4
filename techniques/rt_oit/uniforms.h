// rt (transparency)'s parameters, declared once for the C++ and the GLSL
// (render/common/uniform_block.h).
#ifndef SB_RT_OIT_UNIFORMS_H
#define SB_RT_OIT_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/rt_oit/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(RtOitParams, SB_SLOT_RT_OIT_PARAMS)
  SB_FIELD(mat4, rtoInvViewProj)  // the camera's NDC (window z 0..1) to world: the primary rays
  SB_FIELD(uvec4, rtoSize)        // frame width, height, k (0: all hits), max_hits (0: no cap)
SB_UNIFORM_BLOCK_END(RtOitParams)
// clang-format on

#endif  // SB_RT_OIT_UNIFORMS_H
