// The GLSL math of mboit_math.glsl, compiled as C++ for tests.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::dot;
using glm::floatBitsToUint;
using glm::floor;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using std::abs;
using std::exp;
using std::log;
#define SB_INLINE inline
#define SB_PRECISE
#include "techniques/mboit/mboit_math.glsl"
#undef SB_INLINE
#undef SB_PRECISE
}  // namespace sb::glsl
