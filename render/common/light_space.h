// lightDistance of light_space.glsl compiled as C++: the CPU side of the
// opacity techniques (slice placement) and tests use the shaders' function.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::dot;
using glm::mat4;
using glm::vec3;
#define SB_LIGHT_SPACE_CPU
#define SB_INLINE inline
#include "render/common/light_space.glsl"
#undef SB_INLINE
#undef SB_LIGHT_SPACE_CPU
}  // namespace sb::glsl
