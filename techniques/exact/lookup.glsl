// Exact self-shadowing ("opacity maps with infinitely many slices"): the
// visibility of a point is (1 - alpha_s)^n, n = the hair fragments in front of
// it in its light texel, found by binary search in the texel's sorted list;
// times 0 when the opaque mesh is in front (hard shadow).
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

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(exactViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float z = ndc.z - exactParams.x;
  if (opaqueVisibility(ndc, exactParams.x) == 0.0) return 0.0;
  uint size = uint(exactParams.y);
  uvec2 t = min(uvec2(uv * exactParams.y), uvec2(size - 1u));
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
