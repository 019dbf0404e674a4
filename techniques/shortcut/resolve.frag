// shortcut resolve: the claimed nearest fragments front to back, then the
// tail's weighted average behind them with the tail's own coverage (the
// product of (1 - alpha) of all fragments over that of the nearest ones);
// writes (hair, T) with blending One, SrcAlpha over the opaque colour.
#include "render/common/view.glsl"
#include "render/common/fragment_key.glsl"
#include "shortcut.glsl"
#include "shortcut_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_SHORTCUT_TAIL) uniform sampler2D tailTex;
layout(binding = SB_SLOT_SHORTCUT_REVEALAGE) uniform sampler2D revealageTex;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  uint base = pixelIndex(viewViewport.x) * uint(SB_SHORTCUT_K);
  // Slots hold ascending depths already (the atomic-min chain): blend in slot order.
  vec3 near = vec3(0.0);
  float tNear = 1.0;
  for (int i = 0; i < SB_SHORTCUT_K; ++i) {
    uint slot = base + uint(i);
    if (scClaims[slot] == 0u) continue;
    vec4 f = scColors[slot];
    near += tNear * f.a * f.rgb;
    tNear *= 1.0 - f.a;
  }
  outColor = shortcutResolve(near, tNear, texelFetch(tailTex, px, 0),
                             texelFetch(revealageTex, px, 0).x);
}
