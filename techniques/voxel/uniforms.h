// voxel's parameters (its pass and lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_VOXEL_UNIFORMS_H
#define SB_VOXEL_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/voxel/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(VoxelParams, SB_SLOT_VOXEL_PARAMS)
  SB_FIELD(mat4, voxelViewProj)
  SB_FIELD(vec4, voxelParams)  // x: bias (light depth units), y: splat size, z: shadow alpha,
                               // w: density_scale
  SB_FIELD(vec4, voxelRange)   // x, y: the hair's near and far light depth, z: steps
  SB_FIELD(vec4, voxelCells)   // x: columns per side min(grid, size), y: slices (grid)
SB_UNIFORM_BLOCK_END(VoxelParams)
// clang-format on

#endif  // SB_VOXEL_UNIFORMS_H
