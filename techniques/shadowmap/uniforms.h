// shadowmap's lookup parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_SHADOWMAP_UNIFORMS_H
#define SB_SHADOWMAP_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/shadowmap/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(ShadowMapParams, SB_SLOT_SHADOWMAP_PARAMS)
  SB_FIELD(mat4, shadowViewProj)
  SB_FIELD(vec4, shadowParams)  // bias (light depth units), 0, 0, 0
SB_UNIFORM_BLOCK_END(ShadowMapParams)
// clang-format on

#endif  // SB_SHADOWMAP_UNIFORMS_H
