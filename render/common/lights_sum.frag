// Adds an extra light's colour into the frame's (blend One, One): the frame is
// the sum of every light's shading (render/frame/renderer.h).
#include "slots.h"

layout(binding = SB_SLOT_LIGHTS_SUM_COLOR) uniform sampler2D lightColor;
layout(location = 0) out vec4 outColor;

void main() { outColor = texelFetch(lightColor, ivec2(gl_FragCoord.xy), 0); }
