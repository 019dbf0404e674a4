// stochastic's pass parameters.
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_STOCHASTIC_UNIFORMS_H
#define SB_STOCHASTIC_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/stochastic/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(StochasticParams, SB_SLOT_STOCH_PARAMS)
  SB_FIELD(uvec4, stochParams)  // seed, samples S, -, -
SB_UNIFORM_BLOCK_END(StochasticParams)
// clang-format on

#endif  // SB_STOCHASTIC_UNIFORMS_H
