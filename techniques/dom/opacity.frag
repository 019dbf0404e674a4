// Step 2: every hair fragment adds 1 to the layer it falls in and to every
// layer behind it (additive blending); channel 0 of target 0 (z0) gets 0.
#include "dom.glsl"
#include "../common/opacity.glsl"

layout(binding = 9) uniform sampler2D domDepth;

layout(location = 0) out vec4 domOut0;
#if SB_DOM_TARGETS > 1
layout(location = 1) out vec4 domOut1;
#endif
#if SB_DOM_TARGETS > 2
layout(location = 2) out vec4 domOut2;
#endif
#if SB_DOM_TARGETS > 3
layout(location = 3) out vec4 domOut3;
#endif
#if SB_DOM_TARGETS > 4
layout(location = 4) out vec4 domOut4;
#endif
#if SB_DOM_TARGETS > 5
layout(location = 5) out vec4 domOut5;
#endif

float domValue(int j, float dz) {
  if (j < 1 || j > domLayout.x) return 0.0;
  return domContribution(dz, j, domLayout.x, domLayout.z);
}

vec4 domTarget(int t, float dz) {
  return vec4(domValue(4 * t, dz), domValue(4 * t + 1, dz), domValue(4 * t + 2, dz),
              domValue(4 * t + 3, dz));
}

void main() {
  float z0 = texelFetch(domDepth, ivec2(gl_FragCoord.xy), 0).r;
  float dz = max(gl_FragCoord.z - z0, 0.0);
  domOut0 = domTarget(0, dz);
#if SB_DOM_TARGETS > 1
  domOut1 = domTarget(1, dz);
#endif
#if SB_DOM_TARGETS > 2
  domOut2 = domTarget(2, dz);
#endif
#if SB_DOM_TARGETS > 3
  domOut3 = domTarget(3, dz);
#endif
#if SB_DOM_TARGETS > 4
  domOut4 = domTarget(4, dz);
#endif
#if SB_DOM_TARGETS > 5
  domOut5 = domTarget(5, dz);
#endif
}
