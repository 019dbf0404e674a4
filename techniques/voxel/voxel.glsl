// Parameters and the density grid of voxelized hair density (splat and lookup).
#include "slots.h"
#include "uniforms.h"
// Fragment counts, voxel (x, y, slice) at (slice * columns + y) * columns + x.
layout(std430, binding = SB_SLOT_VOXEL_GRID) buffer VoxelGrid { uint voxelCounts[]; };
// Normalised depth u in [0, 1] over the hair's depth range.
float voxelDepth(float z) { return (z - voxelRange.x) / max(voxelRange.y - voxelRange.x, 1e-12); }
