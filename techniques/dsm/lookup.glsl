// Deep shadow maps lookup: the point's texel curve, searched for the first
// node at or behind the point's light depth and interpolated from the node in
// front of it (dsm_math.glsl); 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "slots.h"
#include "dsm_math.glsl"

#include "uniforms.h"
layout(std430, binding = SB_SLOT_DSM_KEPT) readonly buffer DsmKept { uint dsmKept[]; };
layout(std430, binding = SB_SLOT_DSM_OFFSETS) readonly buffer DsmOffsets { uint dsmOffsets[]; };
layout(std430, binding = SB_SLOT_DSM_NODES) readonly buffer DsmNodes { vec2 dsmNodes[]; };

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(dsmViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float z = ndc.z - dsmParams.x;
  if (opaqueVisibility(ndc, dsmParams.x) == 0.0) return 0.0;
  uint size = uint(dsmParams.y);
  uvec2 t = min(uvec2(uv * dsmParams.y), uvec2(size - 1u));
  uint texel = t.y * size + t.x;
  uint n = dsmKept[texel];
  if (n == 0u) return 1.0;
  uint base = dsmOffsets[texel];
  uint lo = 0u, hi = n;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (dsmNodes[base + mid].x < z) lo = mid + 1u; else hi = mid;
  }
  if (lo == 0u) return dsmValue(dsmNodes[base].y);
  if (lo == n) return dsmValue(dsmNodes[base + n - 1u].y);
  return dsmInterpolate(dsmNodes[base + lo - 1u], dsmNodes[base + lo], z);
}
