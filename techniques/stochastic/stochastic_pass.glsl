// What the two multisampled hair passes of stochastic transparency share: the
// params and the opaque depth they test in the shader (the opaque depth has
// one sample, so it cannot be their attachment).
#include "../common/slots.h"

layout(std140, binding = SB_SLOT_STOCH_PARAMS) uniform StochasticParams {
  uvec4 stochParams;  // seed, group, samples per group, opaque drawn
};
layout(binding = SB_SLOT_STOCH_OPAQUE_DEPTH) uniform sampler2D stochOpaqueDepth;

// Hair at or behind the opaque surface is not seen (the opaque depth test of
// the single-sampled passes: Less).
bool behindOpaque() {
  return stochParams.w != 0u &&
         gl_FragCoord.z >= texelFetch(stochOpaqueDepth, ivec2(gl_FragCoord.xy), 0).r;
}
