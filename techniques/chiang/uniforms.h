// chiang's parameters in the hair shading passes (its shading.glsl), as chiang.glsl's
// chiang() takes them.
// Declared once for the C++ and the GLSL (techniques/common/uniform_block.h).
#ifndef SB_CHIANG_UNIFORMS_H
#define SB_CHIANG_UNIFORMS_H

#include "techniques/common/slots.h"
#include "techniques/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(ChiangParams, SB_SLOT_SHADING_MODEL)
  SB_FIELD(vec4, chiangVariance)  // M_p's variances: R, TT, TRT, the higher orders
  SB_FIELD(vec4, chiangTilt1)     // sin, cos of the scales' tilt alpha and of 2 alpha
  SB_FIELD(vec4, chiangTilt4)     // sin, cos of 4 alpha; 1 / the colour's divisor
                                  // (sqrt(sigma_a) = |ln c| / divisor); the table's range
                                  // of sqrt(sigma_a)
SB_UNIFORM_BLOCK_END(ChiangParams)
// clang-format on

#endif  // SB_CHIANG_UNIFORMS_H
