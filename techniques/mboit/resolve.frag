// mboit resolve: writes (hair, T) with blending One, SrcAlpha over the opaque
// colour (mboit_math.glsl, mboitResolve).
#include "mboit_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_MBOIT_B0) uniform sampler2D b0Tex;
layout(binding = SB_SLOT_MBOIT_ACCUM) uniform sampler2D accumTex;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outColor = mboitResolve(texelFetch(accumTex, p, 0), texelFetch(b0Tex, p, 0).x);
}
