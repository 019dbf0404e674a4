// adsm's lookup parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_ADSM_UNIFORMS_H
#define SB_ADSM_UNIFORMS_H

#include "techniques/adsm/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(AdsmParams, SB_SLOT_ADSM_PARAMS)
  SB_FIELD(mat4, adsmViewProj)
  SB_FIELD(vec4, adsmParams)  // x: bias (light depth units), y: map size, z: shadow alpha
  SB_FIELD(vec4, adsmFiber)   // x: world units per light depth unit, y: fiber depth
                              // (spacing x radius), z: kernel taps per side
SB_UNIFORM_BLOCK_END(AdsmParams)
// clang-format on

#endif  // SB_ADSM_UNIFORMS_H
