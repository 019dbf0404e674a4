// The GLSL math of fom_math.glsl, compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::clamp;
using glm::cos;
using glm::exp;
using glm::log;
using glm::min;
using glm::sin;
inline const float* fomCoeffCpu = nullptr;  // stored floats 0..2n
#define SB_INLINE inline
#define SB_FOM_COEFF(j) fomCoeffCpu[j]
#include "techniques/fom/fom_math.glsl"
#undef SB_FOM_COEFF
#undef SB_INLINE
}  // namespace sb::glsl
