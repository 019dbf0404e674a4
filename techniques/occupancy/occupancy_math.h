// The GLSL math of occupancy_math.glsl, compiled as C++ for tests.
#pragma once

#include <bit>
#include <cstdint>
#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::max;
using glm::min;
using glm::pow;
using uint = uint32_t;
inline int bitCount(uint x) { return std::popcount(x); }
#define SB_INLINE inline
#include "techniques/occupancy/occupancy_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
