// The GLSL math of rt_oit_math.glsl compiled as C++, for its tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::mat4;
using glm::normalize;
using glm::uvec2;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#define SB_OUT(T) T&
#include "techniques/rt_oit/rt_oit_math.glsl"
#undef SB_OUT
#undef SB_INLINE
}  // namespace sb::glsl
