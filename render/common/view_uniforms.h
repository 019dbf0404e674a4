// A view's uniforms (binding 0 in every geometry pass): camera or light.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_COMMON_VIEW_UNIFORMS_H
#define SB_COMMON_VIEW_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(ViewUniforms, SB_SLOT_VIEW)
  SB_FIELD(mat4, viewProj)
  SB_FIELD(vec4, viewEye)       // xyz position; w: 1 perspective, 0 orthographic
  SB_FIELD(vec4, viewForward)   // view direction (orthographic views)
  SB_FIELD(vec4, viewViewport)  // width, height, ribbon width in pixels, world thickness
                                // where a point has none (--primitive world)
SB_UNIFORM_BLOCK_END(ViewUniforms)
// clang-format on

#endif  // SB_COMMON_VIEW_UNIFORMS_H
