// Parameters and the density grid of voxelized hair density (splat and lookup).
#include "slots.h"
layout(std140, binding = SB_SLOT_VOXEL_PARAMS) uniform VoxelParams {
  mat4 voxelViewProj;
  vec4 voxelParams;  // x: bias (light depth units), y: splat size, z: shadow alpha, w: density_scale
  vec4 voxelRange;   // x, y: the hair's near and far light depth, z: steps
  vec4 voxelCells;   // x: columns per side min(grid, size), y: slices (grid)
};
// Fragment counts, voxel (x, y, slice) at (slice * columns + y) * columns + x.
layout(std430, binding = SB_SLOT_VOXEL_GRID) buffer VoxelGrid { uint voxelCounts[]; };
// Normalised depth u in [0, 1] over the hair's depth range.
float voxelDepth(float z) { return (z - voxelRange.x) / max(voxelRange.y - voxelRange.x, 1e-12); }
