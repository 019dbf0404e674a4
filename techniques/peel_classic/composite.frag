// Classic depth peeling: the front-to-back accumulation (premultiplied, alpha
// = coverage) over the opaque colour as (hair, T), blend One, SrcAlpha.
#include "slots.h"

layout(binding = SB_SLOT_PEELC_UNDER) uniform sampler2D peelUnder;
layout(location = 0) out vec4 outColor;

void main() {
  vec4 acc = texelFetch(peelUnder, ivec2(gl_FragCoord.xy), 0);
  outColor = vec4(acc.rgb, 1.0 - acc.a);
}
