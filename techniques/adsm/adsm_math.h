// The GLSL math of adsm_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::exp;
using glm::max;
using glm::pow;
#define SB_INLINE inline
#include "techniques/adsm/adsm_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
