// The GLSL math of mlab_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::uvec2;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#define SB_INOUT(T) T&
#include "techniques/mlab/mlab_math.glsl"
#undef SB_INOUT
#undef SB_INLINE
}  // namespace sb::glsl
