// Exact self-shadowing ("opacity maps with infinitely many slices"): the
// visibility of a point is (1 - alpha_s)^n, n = the hair fragments in front of
// it in its light texel, found by binary search in the texel's sorted list;
// times 0 when the opaque mesh is in front (hard shadow).
#include "render/common/light_jitter.glsl"
#include "render/common/opaque_shadow.glsl"
#include "render/common/slots.h"

// Only the blocks the lookup reads (GL counts declared blocks per stage): a
// texel's list ends where the next one starts (the offsets hold the total last).
#include "uniforms.h"
layout(std430, binding = SB_SLOT_EXACT_OFFSETS) readonly buffer ExactOffsets {
  uint exactOffsets[];
};
#define SB_EXACT_NODES_READONLY
#include "nodes.glsl"

// The visibility in light texel t of a point at window depth z.
float exactVisibilityAt(uvec2 t, float z) {
  uint size = uint(exactParams.y);
  uint texel = t.y * size + t.x;
  uint base = exactOffsets[texel];
  uint lo = 0u, hi = exactOffsets[texel + 1u] - base;
  uint zBits = floatBitsToUint(max(z, 0.0));
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (exactNode(base + mid).x < zBits) lo = mid + 1u; else hi = mid;
  }
  // pow(0, 0) is undefined in GLSL: no fragment in front means fully lit.
  return lo == 0u ? 1.0 : pow(1.0 - exactParams.z, float(lo));
}

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(exactViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float z = ndc.z - exactParams.x;
  if (opaqueVisibility(ndc, exactParams.x) == 0.0) return 0.0;
  uint size = uint(exactParams.y);
#if SB_EXACT_JITTER_SAMPLES > 0
  // jitter=on: the lookup jittered as occupancy's jitter=on is, averaged over as many lookups
  // (the reference of a jittered lookup; harness/references/exact/unit.cpp referenceShadowSpec).
  vec2 texelPos = uv * exactParams.y;
  float sum = 0.0;
  for (int j = 0; j < SB_EXACT_JITTER_SAMPLES; ++j) {
    vec2 p = texelPos + lightTexelJitter(lightJitterSeed(texelPos, ndc.z, exactParams.y, j));
    sum += exactVisibilityAt(uvec2(clamp(ivec2(floor(p)), ivec2(0), ivec2(size - 1u))), z);
  }
  return sum / float(SB_EXACT_JITTER_SAMPLES);
#else
  return exactVisibilityAt(min(uvec2(uv * exactParams.y), uvec2(size - 1u)), z);
#endif
}
