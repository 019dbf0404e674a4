// Weighted sum / weighted average resolve: a full-screen pass that writes
// (hair, T) with blending One, SrcAlpha over the opaque colour (weighted_math.glsl).
#include "weighted_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_WEIGHTED_ACCUM) uniform sampler2D accumTex;
#ifdef SB_WEIGHTED_COUNT
layout(binding = SB_SLOT_WEIGHTED_COUNT) uniform sampler2D countTex;
#endif
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 accum = texelFetch(accumTex, p, 0);
#ifdef SB_WEIGHTED_COUNT
  outColor = weightedAverageResolve(accum, texelFetch(countTex, p, 0).x);
#else
  outColor = weightedSumResolve(accum);
#endif
}
