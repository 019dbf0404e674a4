// AVSM without fragment-shader interlock, one light texel per invocation: the
// paper streams each fragment into its texel's curve in the light pass with
// ordered per-texel read-modify-write. Here the fragments are stored first
// (the exact technique's light-space lists, sorted in submission order:
// primitive id, then depth, the order ordered interlock guarantees), and this
// pass streams them into the curve in that order, so the curve is the one the
// paper's single pass would give; the cost is not (timing marked emulated).
// The nodes go to [p * (SB_AVSM_NODES + 2), ... + count).
#include "render/common/invocation.glsl"
#include "render/common/slots.h"
#include "slots.h"
#define SB_AVSM_SLOTS (SB_AVSM_NODES + 2)
layout(local_size_x = 64) in;

layout(std430, binding = SB_SLOT_EXACT_CURSOR) readonly buffer ExactCursor { uint exactCursor[]; };
layout(std430, binding = SB_SLOT_EXACT_COUNTS) readonly buffer ExactCounts { uint exactCounts[]; };
layout(std430, binding = SB_SLOT_EXACT_OFFSETS) readonly buffer ExactOffsets {
  uint exactOffsets[];
};
#define SB_EXACT_NODES_READONLY
#include "../exact/nodes.glsl"

layout(std430, binding = SB_SLOT_AVSM_OUT_COUNT) writeonly buffer AvsmCount { uint avsmCount[]; };
layout(std430, binding = SB_SLOT_AVSM_OUT_NODES) buffer AvsmNodes { vec2 avsmNodes[]; };
// x: fragments streamed (the emulated steps), y: nodes removed by the compression
layout(std430, binding = SB_SLOT_AVSM_OUT_STATUS) buffer AvsmStatus { uvec2 avsmStatus; };
#include "resolve_uniforms.h"
// The texel's curve is built in place in its SB_AVSM_SLOTS node slots (the
// budget and the two an insertion adds): a local array dynamically indexed
// gave wrong curves on Mesa's GL (they stopped changing at the first
// removal), the same code in the storage buffer agrees with Vulkan and the CPU.
uint avsmBase;
int avsmCurveCount;
#define SB_AVSM_N(i) avsmNodes[avsmBase + uint(i)]
#define SB_AVSM_COUNT avsmCurveCount
#include "avsm_math.glsl"

void main() {
  uint size = uint(avsmResolve.y);
  uint p = linearInvocation();
  if (p >= size * size) return;
  uint n = min(exactCursor[p], exactCounts[p]);
  uint base = exactOffsets[p];
  avsmBase = p * uint(SB_AVSM_SLOTS);
  avsmCurveCount = 0;
  uint removed = 0u;
  for (uint i = 0u; i < n; ++i)
    removed += uint(avsmInsert(uintBitsToFloat(exactNode(base + i).x), avsmResolve.x,
                               SB_AVSM_NODES));
  avsmCount[p] = uint(avsmCurveCount);
  if (n > 0u) {
    atomicAdd(avsmStatus.x, n);
    atomicAdd(avsmStatus.y, removed);
  }
}
