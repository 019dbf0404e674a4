// dom's parameters (its passes and lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_DOM_UNIFORMS_H
#define SB_DOM_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/dom/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(DomParams, SB_SLOT_DOM_PARAMS)
  SB_FIELD(mat4, domViewProj)
  SB_FIELD(vec4, domParams)   // bias (light depth units), map size, shadow alpha, depth bits
  SB_FIELD(ivec4, domLayout)  // layers K, targets, beyond (layers.glsl kDom*),
                              // filter (opacity_filter.glsl)
  SB_ARRAY(vec4, domD, 8)     // d_0..d_K (K <= 31), 4 per vec4
SB_UNIFORM_BLOCK_END(DomParams)
// clang-format on

#endif  // SB_DOM_UNIFORMS_H
