// The GLSL math of dc_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::max;
using glm::pow;
using glm::sqrt;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/dc/dc_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
