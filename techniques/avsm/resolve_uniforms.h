// avsm's resolve parameters (resolve.comp).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_AVSM_RESOLVE_UNIFORMS_H
#define SB_AVSM_RESOLVE_UNIFORMS_H

#include "techniques/avsm/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(AvsmResolve, SB_SLOT_AVSM_RESOLVE)
  SB_FIELD(vec4, avsmResolve)  // x: transmittance 1 - alpha_s, y: map size
SB_UNIFORM_BLOCK_END(AvsmResolve)
// clang-format on

#endif  // SB_AVSM_RESOLVE_UNIFORMS_H
