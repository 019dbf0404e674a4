// Occupancy map: each hair fragment sets the bit of its slice of the texel's
// depth range; the targets (layers of one array) are OR-ed (logic op), 128
// slices per RGBA32UI.
#include "occupancy_math.glsl"
#include "slots.h"
#include "render/common/light_pass_depth.glsl"

layout(binding = SB_SLOT_OCC_RANGE) uniform sampler2D occRange;  // x: nearest, y: -furthest depth

layout(location = 0) out uvec4 outBits[SB_OCC_WORD_TARGETS];

void main() {
  vec2 r = texelFetch(occRange, ivec2(gl_FragCoord.xy), 0).rg;
  int s = occupancySlice(passDepth(), r.x, -r.y, SB_OCC_SLICES);
  uvec4 word = uvec4(0u);
  word[(s / 32) % 4] = 1u << uint(s % 32);
  int target = s / 128;
  for (int k = 0; k < SB_OCC_WORD_TARGETS; ++k) outBits[k] = target == k ? word : uvec4(0u);
}
