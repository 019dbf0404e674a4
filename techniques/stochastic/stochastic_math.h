// The GLSL math of stochastic_math.glsl, compiled as C++ for tests.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "base/hash.h"  // before the namespace: the GLSL's own #include of it is then empty

namespace sb::glsl {
using glm::clamp;
using glm::vec3;
using glm::vec4;
using uint = uint32_t;
#define SB_INLINE inline
#include "techniques/stochastic/stochastic_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
