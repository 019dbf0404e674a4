// The GLSL math of sadeghi.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::cos;
using glm::dot;
using glm::exp;
using glm::length;
using glm::max;
using glm::min;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/sadeghi/sadeghi.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
