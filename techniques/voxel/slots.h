// voxel: parameters (splat and lookup), the density grid
// Its own binding names, for its C++ (#include "techniques/voxel/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_VOXEL_SLOTS_H
#define SB_VOXEL_SLOTS_H

#define SB_SLOT_VOXEL_PARAMS 8
#define SB_SLOT_VOXEL_GRID 9

#endif  // SB_VOXEL_SLOTS_H
