// rt's parameters (its lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_RT_UNIFORMS_H
#define SB_RT_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/rt/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(RtParams, SB_SLOT_RT_PARAMS)
  SB_FIELD(mat4, rtViewProj)
  SB_FIELD(vec4, rtParams)  // x: bias (light depth units), y: map size, z: shadow alpha, w: rays
  SB_FIELD(vec4, rtLight)   // xyz: point light position, or the direction towards a
                            // directional light; w: 1 point, 0 directional
  SB_FIELD(vec4, rtAxisU)   // xyz: the light view's right axis (world); w: max_hits (0: no cap)
  SB_FIELD(vec4, rtAxisV)   // xyz: the light view's up axis (world); w: world size of one texel
                            // per unit of clip w (2 / (size * projection[0][0]))
SB_UNIFORM_BLOCK_END(RtParams)
// clang-format on

#endif  // SB_RT_UNIFORMS_H
