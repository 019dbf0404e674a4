// Slab map: each hair fragment adds 1 to the count of its slab (a group of
// slices), additive blending into RGBA32F targets (layers of one array), 4
// slabs per target.
#include "occupancy_math.glsl"
#include "slots.h"
#include "render/common/light_pass_depth.glsl"

layout(binding = SB_SLOT_OCC_RANGE) uniform sampler2D occRange;  // x: nearest, y: -furthest depth

layout(location = 0) out vec4 outSlabs[SB_OCC_SLAB_TARGETS];

void main() {
  vec2 r = texelFetch(occRange, ivec2(gl_FragCoord.xy), 0).rg;
  // The slab of the fragment's slice, so slab counts and bits always agree.
  int s = occupancySlice(passDepth(), r.x, -r.y, SB_OCC_SLICES);
  int slab = s / (SB_OCC_SLICES / SB_OCC_SLABS);
  vec4 one = vec4(0.0);
  one[slab % 4] = 1.0;
  int target = slab / 4;
  for (int m = 0; m < SB_OCC_SLAB_TARGETS; ++m) outSlabs[m] = target == m ? one : vec4(0.0);
}
