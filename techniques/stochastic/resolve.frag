// Stochastic transparency resolve with the alpha correction: (hair, T) from
// the summed accumulation and the exact total alpha, blended One, SrcAlpha
// over the opaque colour (stochastic_math.glsl).
#include "slots.h"
#include "stochastic_math.glsl"

layout(binding = SB_SLOT_STOCH_ACCUM) uniform sampler2D stochSum;
layout(binding = SB_SLOT_STOCH_ALPHA) uniform sampler2D stochAlpha;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outColor = stochasticResolve(texelFetch(stochSum, p, 0), texelFetch(stochAlpha, p, 0).r);
}
