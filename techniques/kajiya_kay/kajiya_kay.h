// The GLSL math of kajiya_kay.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::dot;
using glm::max;
using glm::pow;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
#define SB_INLINE inline
#include "techniques/kajiya_kay/kajiya_kay.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
