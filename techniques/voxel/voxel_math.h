// The GLSL math of voxel_math.glsl, compiled as C++ for tests: the counts are
// read from voxelCountsCpu (x fastest, then y, then slice; voxelColumnsCpu
// columns per side).
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::exp;
using glm::floor;
using glm::log;
using glm::max;
using glm::min;
inline const float* voxelCountsCpu = nullptr;
inline int voxelColumnsCpu = 0;
#define SB_INLINE inline
#define SB_VOXEL_COUNT(x, y, s) voxelCountsCpu[((s)*voxelColumnsCpu + (y)) * voxelColumnsCpu + (x)]
#include "techniques/voxel/voxel_math.glsl"
#undef SB_VOXEL_COUNT
#undef SB_INLINE
}  // namespace sb::glsl
