// Occupancy maps (Sintorn & Assarsson 2009): the number of hair fragments in
// front of a point is reconstructed from its light texel's depth range,
// occupancy bits and slab counts (occupancy_math.glsl); visibility is
// (1 - alpha_s)^n, times the opaque mesh's hard shadow. Textures only (no
// storage blocks), fetched without derivatives.
#include "../common/opaque_shadow.glsl"
#include "occupancy_math.glsl"

layout(std140, binding = 8) uniform OccupancyParams {
  mat4 occViewProj;
  vec4 occParams;  // x: bias (light depth units), y: map size, z: shadow alpha
};
layout(binding = 9) uniform sampler2D occRange;  // x: nearest depth, y: -furthest depth
layout(binding = 10) uniform usampler2D occBits0;
#if SB_OCC_WORD_TARGETS > 1
layout(binding = 11) uniform usampler2D occBits1;
#endif
#if SB_OCC_WORD_TARGETS > 2
layout(binding = 12) uniform usampler2D occBits2;
#endif
#if SB_OCC_WORD_TARGETS > 3
layout(binding = 13) uniform usampler2D occBits3;
#endif
#if SB_OCC_SLAB_TARGETS > 0
layout(binding = SB_OCC_SLAB_BINDING0) uniform sampler2D occSlabs0;
#endif
#if SB_OCC_SLAB_TARGETS > 1
layout(binding = SB_OCC_SLAB_BINDING1) uniform sampler2D occSlabs1;
#endif
#if SB_OCC_SLAB_TARGETS > 2
layout(binding = SB_OCC_SLAB_BINDING2) uniform sampler2D occSlabs2;
#endif
#if SB_OCC_SLAB_TARGETS > 3
layout(binding = SB_OCC_SLAB_BINDING3) uniform sampler2D occSlabs3;
#endif

// The paper's anti-aliasing: the lookup moves by up to half a texel. The
// offset is a smooth but fast-varying function of the point's light-space
// position in texels (a few radians per texel), deterministic and, unlike a
// hash of the position's bits, insensitive to the last-bit differences of the
// interpolated position between the two APIs.
vec2 occupancyJitter(vec3 texelSpace) {
  return 0.5 * vec2(sin(dot(texelSpace, vec3(4.1414, 6.2831, 5.3792))),
                    sin(dot(texelSpace, vec3(6.9173, 3.7351, 4.7717))));
}

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(occViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float bias = occParams.x;
  if (opaqueVisibility(ndc, bias) == 0.0) return 0.0;
  vec2 texelPos = uv * occParams.y;
#if SB_OCC_JITTER
  texelPos += occupancyJitter(vec3(texelPos, ndc.z * occParams.y));
#endif
  int size = int(occParams.y);
  ivec2 t = clamp(ivec2(floor(texelPos)), ivec2(0), ivec2(size - 1));
  vec2 r = texelFetch(occRange, t, 0).rg;
  uint bits[SB_OCC_MAX_WORDS];
  for (int i = 0; i < SB_OCC_MAX_WORDS; ++i) bits[i] = 0u;
  uvec4 w = texelFetch(occBits0, t, 0);
  bits[0] = w.x; bits[1] = w.y; bits[2] = w.z; bits[3] = w.w;
#if SB_OCC_WORD_TARGETS > 1
  w = texelFetch(occBits1, t, 0);
  bits[4] = w.x; bits[5] = w.y; bits[6] = w.z; bits[7] = w.w;
#endif
#if SB_OCC_WORD_TARGETS > 2
  w = texelFetch(occBits2, t, 0);
  bits[8] = w.x; bits[9] = w.y; bits[10] = w.z; bits[11] = w.w;
#endif
#if SB_OCC_WORD_TARGETS > 3
  w = texelFetch(occBits3, t, 0);
  bits[12] = w.x; bits[13] = w.y; bits[14] = w.z; bits[15] = w.w;
#endif
  float slabs[SB_OCC_MAX_SLABS];
  for (int i = 0; i < SB_OCC_MAX_SLABS; ++i) slabs[i] = 0.0;
  vec4 f;
#if SB_OCC_SLAB_TARGETS > 0
  f = texelFetch(occSlabs0, t, 0);
  slabs[0] = f.x; slabs[1] = f.y; slabs[2] = f.z; slabs[3] = f.w;
#endif
#if SB_OCC_SLAB_TARGETS > 1
  f = texelFetch(occSlabs1, t, 0);
  slabs[4] = f.x; slabs[5] = f.y; slabs[6] = f.z; slabs[7] = f.w;
#endif
#if SB_OCC_SLAB_TARGETS > 2
  f = texelFetch(occSlabs2, t, 0);
  slabs[8] = f.x; slabs[9] = f.y; slabs[10] = f.z; slabs[11] = f.w;
#endif
#if SB_OCC_SLAB_TARGETS > 3
  f = texelFetch(occSlabs3, t, 0);
  slabs[12] = f.x; slabs[13] = f.y; slabs[14] = f.z; slabs[15] = f.w;
#endif
  float n = occupancyCount(ndc.z - bias, r.x, -r.y, bits, slabs, SB_OCC_SLICES, SB_OCC_SLABS,
                           SB_OCC_SLAB_TARGETS > 0);
  return occupancyVisibility(n, occParams.z);
}
