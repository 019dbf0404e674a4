// chiang's parameters in the hair shading passes (its shading.glsl), as chiang.glsl's
// chiang() and dual.glsl's chiangDual() take them.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_CHIANG_UNIFORMS_H
#define SB_CHIANG_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(ChiangParams, SB_SLOT_SHADING_MODEL)
  SB_FIELD(vec4, chiangVariance)  // M_p's variances: R, TT, TRT, the higher orders
  SB_FIELD(vec4, chiangTilt1)     // sin, cos of the scales' tilt alpha and of 2 alpha
  SB_FIELD(vec4, chiangTilt4)     // sin, cos of 4 alpha; 1 / the colour's divisor
                                  // (sqrt(sigma_a) = |ln c| / divisor); the table's range
                                  // of sqrt(sigma_a)
  SB_FIELD(float, chiangBetaN)    // azimuthal roughness and index of refraction: they choose
  SB_FIELD(float, chiangEta)      // the table (the C++ builds it from them)
  SB_FIELD(float, chiangDensityF) // dual scattering's forward and backward density factors
  SB_FIELD(float, chiangDensityB) // d_f, d_b (dual.glsl)
  SB_FIELD(int, chiangDualScattering)  // 1: scattering=dual (dual.glsl, its table bound)
  SB_FIELD(int, chiangFibreOpacity)    // 1: opacity=fibre, the colour over the fibre's opacity
  SB_FIELD(int, chiangOpacityRow)      // where chiangOpacity's row starts in the table bound
  SB_FIELD(float, chiangUnused0)       // std140 rounds the block to 16 bytes
SB_UNIFORM_BLOCK_END(ChiangParams)
// clang-format on

#endif  // SB_CHIANG_UNIFORMS_H
