// The GLSL math of avsm_math.glsl, compiled as C++ for tests, with room for
// the largest budget (16 nodes, plus the two an insertion adds).
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::max;
using glm::vec2;
#define SB_INLINE inline
#define SB_INOUT(T) T&
#define SB_AVSM_CAP 18
#include "techniques/avsm/avsm_math.glsl"
#undef SB_AVSM_CAP
#undef SB_INOUT
#undef SB_INLINE
}  // namespace sb::glsl
