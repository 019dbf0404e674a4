// Dual depth peeling: this pass's back layer (c, a), blended over the back
// accumulation (SrcAlpha, OneMinusSrcAlpha; alpha: the back transmittance).
#include "slots.h"

layout(binding = SB_SLOT_DUAL_BACK_TEMP) uniform sampler2D dualBackLayer;
layout(location = 0) out vec4 outColor;

void main() { outColor = texelFetch(dualBackLayer, ivec2(gl_FragCoord.xy), 0); }
