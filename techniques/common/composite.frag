// Puts the premultiplied front-to-back accumulation of the hair over what is
// in the target (blend One, OneMinusSrcAlpha): c = acc.rgb + (1 - acc.a) * dst.
#include "view.glsl"
#include "fragment_key.glsl"
#include "slots.h"

layout(std430, binding = SB_SLOT_OIT_ACCUM) readonly buffer Accum { vec4 accum[]; };
layout(location = 0) out vec4 outColor;

void main() { outColor = accum[pixelIndex(viewViewport.x)]; }
