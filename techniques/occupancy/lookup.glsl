// Occupancy maps (Sintorn & Assarsson 2009): the number of hair fragments in
// front of a point is reconstructed from its light texel's depth range,
// occupancy bits and slab counts (occupancy_math.glsl); visibility is
// (1 - alpha_s)^n, times the opaque mesh's hard shadow. Textures only (no
// storage blocks), fetched without derivatives.
#include "render/common/light_jitter.glsl"
#include "render/common/opaque_shadow.glsl"
#include "occupancy_math.glsl"
#include "slots.h"

#include "uniforms.h"
layout(binding = SB_SLOT_OCC_RANGE) uniform sampler2D occRange;  // x: nearest, y: -furthest depth
layout(binding = SB_SLOT_OCC_BITS) uniform usampler2DArray occBits;  // 128 slices per layer
#if SB_OCC_SLAB_TARGETS > 0
layout(binding = SB_SLOT_OCC_SLABS) uniform sampler2DArray occSlabs;  // 4 slabs per layer
#endif

#ifndef SB_OCC_JITTER_SAMPLES
#define SB_OCC_JITTER_SAMPLES 1
#endif

// The visibility from the maps of the texel at texelPos (in texels) for a
// point at light distance z.
float occupancyVisibilityAt(vec2 texelPos, float z) {
  int size = int(occParams.y);
  ivec2 t = clamp(ivec2(floor(texelPos)), ivec2(0), ivec2(size - 1));
  vec2 r = texelFetch(occRange, t, 0).rg;
  uint bits[SB_OCC_MAX_WORDS];
  for (int i = 0; i < SB_OCC_MAX_WORDS; ++i) bits[i] = 0u;
  for (int k = 0; k < SB_OCC_WORD_TARGETS; ++k) {
    uvec4 w = texelFetch(occBits, ivec3(t, k), 0);
    for (int c = 0; c < 4; ++c) bits[4 * k + c] = w[c];
  }
  float slabs[SB_OCC_MAX_SLABS];
  for (int i = 0; i < SB_OCC_MAX_SLABS; ++i) slabs[i] = 0.0;
#if SB_OCC_SLAB_TARGETS > 0
  for (int m = 0; m < SB_OCC_SLAB_TARGETS; ++m) {
    vec4 f = texelFetch(occSlabs, ivec3(t, m), 0);
    for (int c = 0; c < 4; ++c) slabs[4 * m + c] = f[c];
  }
#endif
  float n = occupancyCount(z, r.x, -r.y, bits, slabs, SB_OCC_SLICES, SB_OCC_SLABS,
                           SB_OCC_SLAB_TARGETS > 0);
  return occupancyVisibility(n, occParams.z);
}

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(occViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float bias = occParams.x;
  if (opaqueVisibility(ndc, bias) == 0.0) return 0.0;
  vec2 texelPos = uv * occParams.y;
  float z = lightDistance(occViewProj, ndc.z - bias);  // bias in window depth
#if SB_OCC_JITTER
  // The paper jitters the lookup by up to half a texel and relies on the
  // many fragments blended per pixel to average it; jitter_samples averages
  // that many jittered lookups in the one fragment (1: a single lookup).
  float sum = 0.0;
  for (int j = 0; j < SB_OCC_JITTER_SAMPLES; ++j) {
    vec3 seed = lightJitterSeed(texelPos, ndc.z, occParams.y, j);
    sum += occupancyVisibilityAt(texelPos + lightTexelJitter(seed), z);
  }
  return sum / float(SB_OCC_JITTER_SAMPLES);
#else
  return occupancyVisibilityAt(texelPos, z);
#endif
}
