// The GLSL math of sadeghi.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

#include "techniques/sadeghi/uniforms.h"

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::cos;
using glm::dot;
using glm::exp;
using glm::length;
using glm::max;
using glm::min;
using glm::vec3;
using glm::vec4;
#define SB_INLINE inline
#include "techniques/sadeghi/sadeghi.glsl"
#undef SB_INLINE
}  // namespace sb::glsl

namespace sb {
// The specular sum for the model's block, as its shading.glsl calls it (G_angle and xi_TT in
// the fourth components of sadeghi.glsl's shift and width).
inline glm::vec3 sadeghiSpecular(const SadeghiParams& p, glm::vec3 T, glm::vec3 L, glm::vec3 V,
                                 glm::vec3 color) {
  return glsl::sadeghi(T, L, V, color, glm::vec4(glm::vec3(p.sadeghiAlpha), p.sadeghiGlintAngle),
                       glm::vec4(glm::vec3(p.sadeghiBeta), p.sadeghiTtWidth), p.sadeghiIntensity,
                       p.sadeghiGlintWidth);
}
}  // namespace sb
