// The GLSL math of marschner.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::cos;
using glm::dot;
using glm::exp;
using glm::floor;
using glm::length;
using glm::log;
using glm::max;
using glm::min;
using glm::pow;
using glm::sin;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/marschner/marschner.glsl"
#undef SB_INLINE
#undef SB_PI
}  // namespace sb::glsl
