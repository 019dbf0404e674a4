// Weighted blended OIT resolve: writes (hair, T) with blending One, SrcAlpha
// over the opaque colour (wboit_math.glsl).
#include "wboit_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_WBOIT_ACCUM) uniform sampler2D accumTex;
layout(binding = SB_SLOT_WBOIT_REVEALAGE) uniform sampler2D revealageTex;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outColor = wboitResolve(texelFetch(accumTex, p, 0), texelFetch(revealageTex, p, 0).x);
}
