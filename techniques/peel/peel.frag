// Depth peeling from the eye (Everitt 2001), exact: SB_PEEL_PASS 0 and 1 find
// the next fragment after the previous layer's key (peel_step.glsl); pass 2
// shades that one fragment and adds it under what is accumulated so far.
// Storage writes are side effects: without early tests they would happen even
// for fragments the opaque depth test then rejects.
layout(early_fragment_tests) in;
#include <shadow>

#include "render/common/fragment_key.glsl"
#include "render/common/shading.glsl"
#include "render/common/slots.h"
#include "render/common/view.glsl"
#include "render/shading/hair_shading.glsl"

layout(std430, binding = SB_SLOT_OIT_ACCUM) buffer Accum { vec4 accum[]; };
layout(std430, binding = SB_SLOT_PEEL_STATE) buffer PeelState { uvec4 peelState[]; };
layout(std430, binding = SB_SLOT_PEEL_PEELED) buffer Peeled { uint peeled[]; };
#include "render/common/peel_step.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;

void main() {
  uint p = pixelIndex(viewViewport.x);
  uvec2 key = fragmentKey();
#if SB_PEEL_PASS < 2
  peelStep(p, key);
#else
  if (key != peelState[p].zw) return;  // only this layer's fragment
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  float a = vColor.a;
  vec4 acc = accum[p];
  accum[p] = acc + (1.0 - acc.a) * vec4(c * a, a);
#endif
}
