// Occupancy map: each hair fragment sets the bit of its slice of the texel's
// depth range; the targets are OR-ed (logic op), 128 slices per RGBA32UI.
#include "occupancy_math.glsl"

layout(binding = 9) uniform sampler2D occRange;  // x: nearest depth, y: -furthest depth

layout(location = 0) out uvec4 outBits0;
#if SB_OCC_WORD_TARGETS > 1
layout(location = 1) out uvec4 outBits1;
#endif
#if SB_OCC_WORD_TARGETS > 2
layout(location = 2) out uvec4 outBits2;
#endif
#if SB_OCC_WORD_TARGETS > 3
layout(location = 3) out uvec4 outBits3;
#endif

void main() {
  vec2 r = texelFetch(occRange, ivec2(gl_FragCoord.xy), 0).rg;
  int s = occupancySlice(gl_FragCoord.z, r.x, -r.y, SB_OCC_SLICES);
  uvec4 word = uvec4(0u);
  word[(s / 32) % 4] = 1u << uint(s % 32);
  int target = s / 128;
  outBits0 = target == 0 ? word : uvec4(0u);
#if SB_OCC_WORD_TARGETS > 1
  outBits1 = target == 1 ? word : uvec4(0u);
#endif
#if SB_OCC_WORD_TARGETS > 2
  outBits2 = target == 2 ? word : uvec4(0u);
#endif
#if SB_OCC_WORD_TARGETS > 3
  outBits3 = target == 3 ? word : uvec4(0u);
#endif
}
