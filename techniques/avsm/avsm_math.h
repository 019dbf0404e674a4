// The GLSL math of avsm_math.glsl, compiled as C++ for tests: the curve in
// a CPU struct, with room for the largest budget (16 nodes, plus the two an
// insertion adds), reached through the macros the GLSL reads.
#pragma once

#include <glm/glm.hpp>

namespace sb::glsl {
using glm::abs;
using glm::clamp;
using glm::max;
using glm::vec2;
struct AvsmCurve {
  vec2 n[18] = {};  // (depth, transmittance), front to back
  int count = 0;
};
inline thread_local AvsmCurve* avsmCurveCpu = nullptr;  // the curve the functions work on
#define SB_INLINE inline
#define SB_PRECISE
#define SB_AVSM_N(i) avsmCurveCpu->n[i]
#define SB_AVSM_COUNT avsmCurveCpu->count
#include "techniques/avsm/avsm_math.glsl"
#undef SB_AVSM_COUNT
#undef SB_AVSM_N
#undef SB_PRECISE
#undef SB_INLINE
}  // namespace sb::glsl

namespace sb {
// The GLSL functions on one CPU curve.
inline int avsmStream(glsl::AvsmCurve& c, float d, float t, int budget) {
  glsl::avsmCurveCpu = &c;
  return glsl::avsmInsert(d, t, budget);
}
inline int avsmRemoveOne(glsl::AvsmCurve& c) {
  glsl::avsmCurveCpu = &c;
  return glsl::avsmRemoveOne();
}
inline float avsmValue(glsl::AvsmCurve& c, float z, bool behind) {
  glsl::avsmCurveCpu = &c;
  return glsl::avsmValue(z, behind);
}
}  // namespace sb
