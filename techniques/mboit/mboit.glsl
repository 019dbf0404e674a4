// The parameters of both hair passes of mboit (std140).
#include "slots.h"
layout(std140, binding = SB_SLOT_MBOIT_PARAMS) uniform MboitParams {
  vec4 mboitWarp;  // ln(near), 1 / (ln(far) - ln(near)), bias, overestimation
  ivec4 mboitN;    // x: n (2n real moments beyond b0), y: bits, z: kind (0 power, 1 trig)
};
