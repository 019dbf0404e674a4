// occupancy's lookup parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_OCCUPANCY_UNIFORMS_H
#define SB_OCCUPANCY_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/occupancy/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(OccupancyParams, SB_SLOT_OCC_PARAMS)
  SB_FIELD(mat4, occViewProj)
  SB_FIELD(vec4, occParams)  // x: bias (light depth units), y: map size, z: shadow alpha
SB_UNIFORM_BLOCK_END(OccupancyParams)
// clang-format on

#endif  // SB_OCCUPANCY_UNIFORMS_H
