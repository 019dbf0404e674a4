// Step 2: every hair fragment adds 1 to the layer it falls in and to every
// layer behind it (additive blending; SB_DOM_COUNTING 1: to every layer in
// front of it instead, the thesis's Listing 3). Channel 0 of target 0 is unused (0):
// z0 lives in the depth map only, quantized to the depth bits as it is read.
#include "dom.glsl"
#include "layers.glsl"
#include "render/common/light_space.glsl"
#include "slots.h"

layout(binding = SB_SLOT_DOM_DEPTH) uniform sampler2D domDepth;

// Target t is layer t of the opacity array.
layout(location = 0) out vec4 domOut[SB_DOM_TARGETS];

float domValue(int j, float dz) {
  if (j < 1 || j > domLayout.x) return 0.0;
#if SB_DOM_COUNTING == 1
  return domContributionPreceding(dz, j, domLayout.x, domLayout.z);
#else
  return domContribution(dz, j, domLayout.x, domLayout.z);
#endif
}

vec4 domTarget(int t, float dz) {
  return vec4(domValue(4 * t, dz), domValue(4 * t + 1, dz), domValue(4 * t + 2, dz),
              domValue(4 * t + 3, dz));
}

void main() {
  float zWin = texelFetch(domDepth, ivec2(gl_FragCoord.xy), 0).r;
  float z0 = domQuantize(lightDistance(domViewProj, zWin), int(domParams.w));
  float dz = max(lightDistance(domViewProj, gl_FragCoord.z) - z0, 0.0);
  for (int t = 0; t < SB_DOM_TARGETS; ++t) domOut[t] = domTarget(t, dz);
}
