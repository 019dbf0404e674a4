// Occupancy-ordered blending, resolve pass: the accumulated hair over the
// opaque colour (blend One, OneMinusSrcAlpha): f = hair.rgb + (1 - Lambda) b,
// with 1 - Lambda = prod (1 - a_i) ((1 - a)^n for one alpha) and, unless
// SB_OIT_LAMBDA is 0, the paper's renormalisation hair.rgb * Lambda / hair.a
// (occupancy_oit_math.glsl); SB_OIT_LAMBDA 2 (order=printed): as printed,
// hair.rgb * hair.a / Lambda.
#include "../occupancy/occupancy_math.glsl"
#include "occupancy_oit_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_OOIT_ACCUM) uniform sampler2D oitAccum;
layout(binding = SB_SLOT_OOIT_LOG2T) uniform sampler2D oitLog2T;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
#if SB_OIT_LAMBDA == 2
  outColor = oitResolvePrinted(texelFetch(oitAccum, t, 0), texelFetch(oitLog2T, t, 0).r);
#else
  outColor = oitResolve(texelFetch(oitAccum, t, 0), texelFetch(oitLog2T, t, 0).r,
                        SB_OIT_LAMBDA != 0);
#endif
}
