// shortcut pass 1 (TressFX ShortCut's "depths alpha" pass): the k nearest
// window depths of the pixel by a chain of atomic mins (each slot keeps the
// smaller value and passes the larger one on, so slot i ends as the i-th
// smallest depth), and 1 - alpha multiplied into the revealage target (blend
// Zero, OneMinusSrcColor).
// Storage writes are side effects: early tests keep hair behind the opaque
// depth out of them.
layout(early_fragment_tests) in;
#include "render/common/view.glsl"
#include "render/common/fragment_key.glsl"
#include "shortcut.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outRevealage;

void main() {
  uint base = pixelIndex(viewViewport.x) * uint(SB_SHORTCUT_K);
  uint d = floatBitsToUint(gl_FragCoord.z);
  for (int i = 0; i < SB_SHORTCUT_K; ++i) {
    uint previous = atomicMin(scDepths[base + uint(i)], d);
    d = max(d, previous);
  }
  outRevealage = vec4(vColor.a);
}
