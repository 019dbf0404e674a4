// What the depth and accumulation passes of stochastic transparency share:
// the params and the S sample depths per pixel (uint bits of the window
// depth: for depths in [0, 1] their order is the floats' order).
#include "slots.h"

layout(std140, binding = SB_SLOT_STOCH_PARAMS) uniform StochasticParams {
  uvec4 stochParams;  // seed, samples S, -, -
};
layout(std430, binding = SB_SLOT_STOCH_DEPTHS) buffer StochasticDepths { uint stochDepths[]; };
