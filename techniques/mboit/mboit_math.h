// The GLSL math of mboit_math.glsl, compiled as C++ for tests.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::max;
using glm::min;
using glm::mix;
using glm::vec3;
using glm::vec4;
using std::abs;
using std::exp;
using std::log;
#define SB_INLINE inline
#include "techniques/mboit/mboit_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
