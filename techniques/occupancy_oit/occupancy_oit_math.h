// The GLSL math of occupancy_oit_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

#include "techniques/occupancy/occupancy_math.h"

namespace sb::glsl {
using glm::clamp;
using glm::exp2;
using glm::log2;
using glm::max;
using glm::min;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/occupancy_oit/occupancy_oit_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
