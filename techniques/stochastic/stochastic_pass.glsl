// What the depth and accumulation passes of stochastic transparency share:
// the params and the S sample depths per pixel (uint bits of the window
// depth: for depths in [0, 1] their order is the floats' order).
#include "slots.h"

#include "uniforms.h"
layout(std430, binding = SB_SLOT_STOCH_DEPTHS) buffer StochasticDepths { uint stochDepths[]; };
