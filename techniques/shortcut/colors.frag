// shortcut pass 2: a fragment whose depth is one of the pixel's k nearest
// claims that slot (atomicCompSwap: of fragments tied in depth, as many as
// there are equal slots) and stores its shaded colour there, to be blended in
// depth order by the resolve; every other fragment adds (c a, a) to the tail
// target, the weighted average of TressFX's ShortCut.
layout(early_fragment_tests) in;
#include "render/common/view.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "render/common/fragment_key.glsl"
#include "shortcut.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outTail;

void main() {
  uint base = pixelIndex(viewViewport.x) * uint(SB_SHORTCUT_K);
  uint d = floatBitsToUint(gl_FragCoord.z);
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  float a = vColor.a;
  for (int i = 0; i < SB_SHORTCUT_K; ++i) {
    uint slot = base + uint(i);
    if (scDepths[slot] == d && atomicCompSwap(scClaims[slot], 0u, 1u) == 0u) {
      scColors[slot] = vec4(c, a);
      outTail = vec4(0.0);
      return;
    }
  }
  outTail = vec4(c * a, a);
}
