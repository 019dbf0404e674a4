// Puts the premultiplied front-to-back accumulation of the hair over what is
// in the target (blend One, OneMinusSrcAlpha): c = acc.rgb + (1 - acc.a) * dst.
#include "fragment_key.glsl"
#include "slots.h"
#include "view.glsl"

layout(std430, binding = SB_SLOT_OIT_ACCUM) readonly buffer Accum { vec4 accum[]; };
layout(location = 0) out vec4 outColor;

void main() { outColor = accum[pixelIndex(viewViewport.x)]; }
