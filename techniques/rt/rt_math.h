// The GLSL math of rt_math.glsl compiled as C++, for the CPU BVH and its tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::dot;
using glm::fract;
using glm::max;
using glm::min;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/rt/rt_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
