// AVSM without fragment-shader interlock, one light texel per invocation: the
// paper streams each fragment into its texel's curve in the light pass with
// ordered per-texel read-modify-write. Here the fragments are stored first
// (the exact technique's light-space lists, sorted in submission order:
// primitive id, then depth, the order ordered interlock guarantees), and this
// pass streams them into the curve in that order, so the curve is the one the
// paper's single pass would give; the cost is not (timing marked emulated).
// The nodes go to [p * SB_AVSM_NODES, p * SB_AVSM_NODES + count).
#include "../common/invocation.glsl"
#include "../common/slots.h"
#define SB_AVSM_CAP (SB_AVSM_NODES + 2)
#include "avsm_math.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = SB_SLOT_EXACT_CURSOR) readonly buffer ExactCursor { uint exactCursor[]; };
layout(std430, binding = SB_SLOT_EXACT_COUNTS) readonly buffer ExactCounts { uint exactCounts[]; };
layout(std430, binding = SB_SLOT_EXACT_OFFSETS) readonly buffer ExactOffsets {
  uint exactOffsets[];
};
layout(std430, binding = SB_SLOT_EXACT_NODES) readonly buffer ExactNodes { uvec2 exactNodes[]; };

layout(std430, binding = SB_SLOT_AVSM_OUT_COUNT) writeonly buffer AvsmCount { uint avsmCount[]; };
layout(std430, binding = SB_SLOT_AVSM_OUT_NODES) writeonly buffer AvsmNodes { vec2 avsmNodes[]; };
// x: fragments streamed (the emulated steps), y: nodes removed by the compression
layout(std430, binding = SB_SLOT_AVSM_OUT_STATUS) buffer AvsmStatus { uvec2 avsmStatus; };
layout(std140, binding = SB_SLOT_AVSM_RESOLVE) uniform AvsmResolve {
  vec4 avsmResolve;  // x: transmittance 1 - alpha_s, y: map size
};

void main() {
  uint size = uint(avsmResolve.y);
  uint p = linearInvocation();
  if (p >= size * size) return;
  uint n = min(exactCursor[p], exactCounts[p]);
  uint base = exactOffsets[p];
  AvsmCurve c = avsmEmpty();
  uint removed = 0u;
  for (uint i = 0u; i < n; ++i)
    removed += uint(avsmInsert(c, uintBitsToFloat(exactNodes[base + i].x), avsmResolve.x,
                               SB_AVSM_NODES));
  avsmCount[p] = uint(c.count);
  for (int k = 0; k < c.count; ++k) avsmNodes[p * uint(SB_AVSM_NODES) + uint(k)] = c.n[k];
  if (n > 0u) {
    atomicAdd(avsmStatus.x, n);
    atomicAdd(avsmStatus.y, removed);
  }
}
