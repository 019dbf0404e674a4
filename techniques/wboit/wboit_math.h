// The GLSL math of wboit_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::max;
using glm::min;
using glm::pow;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/wboit/wboit_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
