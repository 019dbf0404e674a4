// Classic depth peeling: the layer blended under the accumulation (blend
// OneMinusDstAlpha, One: acc += (1 - acc.a) (a c, a)), and one peeled
// fragment counted where the layer has one (its depth is not the clear 2).
#include "slots.h"

layout(binding = SB_SLOT_PEELC_LAYER_COLOR) uniform sampler2D peelLayerColor;
layout(binding = SB_SLOT_PEELC_LAYER_DEPTH) uniform sampler2D peelLayerDepth;
layout(location = 0) out vec4 outUnder;
layout(location = 1) out vec4 outPeeled;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outUnder = texelFetch(peelLayerColor, p, 0);
  outPeeled = vec4(texelFetch(peelLayerDepth, p, 0).r < 1.5 ? 1.0 : 0.0);
}
