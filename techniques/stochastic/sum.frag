// Stochastic transparency: one group's resolved accumulation added into the
// sum over groups (additive blending); S = groups x samples per group.
#include "../common/slots.h"

layout(binding = SB_SLOT_STOCH_ACCUM) uniform sampler2D stochAccum;
layout(location = 0) out vec4 outSum;

void main() { outSum = texelFetch(stochAccum, ivec2(gl_FragCoord.xy), 0); }
