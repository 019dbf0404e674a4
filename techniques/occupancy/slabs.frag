// Slab map: each hair fragment adds 1 to the count of its slab (a group of
// slices), additive blending into RGBA32F targets, 4 slabs per target.
#include "occupancy_math.glsl"

layout(binding = 9) uniform sampler2D occRange;  // x: nearest depth, y: -furthest depth

layout(location = 0) out vec4 outSlabs0;
#if SB_OCC_SLAB_TARGETS > 1
layout(location = 1) out vec4 outSlabs1;
#endif
#if SB_OCC_SLAB_TARGETS > 2
layout(location = 2) out vec4 outSlabs2;
#endif
#if SB_OCC_SLAB_TARGETS > 3
layout(location = 3) out vec4 outSlabs3;
#endif

void main() {
  vec2 r = texelFetch(occRange, ivec2(gl_FragCoord.xy), 0).rg;
  // The slab of the fragment's slice, so slab counts and bits always agree.
  int s = occupancySlice(gl_FragCoord.z, r.x, -r.y, SB_OCC_SLICES);
  int slab = s / (SB_OCC_SLICES / SB_OCC_SLABS);
  vec4 one = vec4(0.0);
  one[slab % 4] = 1.0;
  int target = slab / 4;
  outSlabs0 = target == 0 ? one : vec4(0.0);
#if SB_OCC_SLAB_TARGETS > 1
  outSlabs1 = target == 1 ? one : vec4(0.0);
#endif
#if SB_OCC_SLAB_TARGETS > 2
  outSlabs2 = target == 2 ? one : vec4(0.0);
#endif
#if SB_OCC_SLAB_TARGETS > 3
  outSlabs3 = target == 3 ? one : vec4(0.0);
#endif
}
