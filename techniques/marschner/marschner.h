// The GLSL math of marschner.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

#include "techniques/marschner/uniforms.h"

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

namespace sb {
// The scattering function S for the model's block, as its shading.glsl calls it (eta and the
// caustic floor in the fourth components of marschner.glsl's shift and width).
inline glm::vec3 marschnerScattering(const MarschnerParams& p, glm::vec3 T, glm::vec3 L,
                                     glm::vec3 V, glm::vec3 color) {
  return glsl::marschner(T, L, V, color, glm::vec4(glm::vec3(p.marschnerAlpha), p.marschnerEta),
                         glm::vec4(glm::vec3(p.marschnerBeta), p.marschnerCaustic));
}
}  // namespace sb
