// The GLSL math of shortcut_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/shortcut/shortcut_math.glsl"
#undef SB_INLINE
}  // namespace sb::glsl
