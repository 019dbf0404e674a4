// Dual depth peeling, final: front (premultiplied, alpha = coverage) over the
// back (colour, transmittance) over the opaque colour, as (hair, T) for blend
// One, SrcAlpha: hair = F + (1 - F.a) B, T = (1 - F.a) T_back.
#include "slots.h"

layout(binding = SB_SLOT_DUAL_FRONT_FINAL) uniform sampler2D dualFront;
layout(binding = SB_SLOT_DUAL_BACK_FINAL) uniform sampler2D dualBack;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 f = texelFetch(dualFront, p, 0);
  vec4 b = texelFetch(dualBack, p, 0);
  outColor = vec4(f.rgb + (1.0 - f.a) * b.rgb, (1.0 - f.a) * b.a);
}
