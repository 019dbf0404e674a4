// Deep shadow maps, one texel per invocation: its exact visibility function
// from the light-space fragment lists the exact technique builds and sorts
// (techniques/exact/), compressed within epsilon by the greedy algorithm
// (dsm_math.glsl); the nodes it keeps go to the texel's slots
// [dsmOffsets[p], dsmOffsets[p] + capacity), capacity = min(2 n, max nodes).
#include "dsm.glsl"
#include "dsm_math.glsl"
#include "render/common/invocation.glsl"
#include "render/common/slots.h"
#include "slots.h"
layout(local_size_x = 64) in;

layout(std430, binding = SB_SLOT_EXACT_CURSOR) readonly buffer ExactCursor { uint exactCursor[]; };
layout(std430, binding = SB_SLOT_EXACT_COUNTS) readonly buffer ExactCounts { uint exactCounts[]; };
layout(std430, binding = SB_SLOT_EXACT_OFFSETS) readonly buffer ExactOffsets {
  uint exactOffsets[];
};
#define SB_EXACT_NODES_READONLY
#include "../exact/nodes.glsl"

layout(std430, binding = SB_SLOT_DSM_OUT_KEPT) writeonly buffer DsmKept { uint dsmKept[]; };
layout(std430, binding = SB_SLOT_DSM_OUT_OFFSETS) readonly buffer DsmOffsets { uint dsmOffsets[]; };
layout(std430, binding = SB_SLOT_DSM_OUT_NODES) writeonly buffer DsmNodes { vec2 dsmNodes[]; };
// x: texels cut at max nodes
layout(std430, binding = SB_SLOT_DSM_OUT_STATUS) buffer DsmStatus { uint dsmTruncated; };

uint dsmBase, dsmCapacity, dsmCount;
bool dsmCut;

void dsmKeep(DsmEmit e) {
  for (int i = 0; i < e.count; ++i) {
    if (dsmCount >= dsmCapacity) {
      dsmCut = true;
      return;
    }
    dsmNodes[dsmBase + dsmCount] = i == 0 ? e.n0 : (i == 1 ? e.n1 : e.n2);
    dsmCount += 1u;
  }
}

void main() {
  uint size = uint(dsmCompress.z);
  uint p = linearInvocation();
  if (p >= size * size) return;
  uint n = min(exactCursor[p], exactCounts[p]);
  uint base = exactOffsets[p];
  dsmBase = dsmOffsets[p];
  dsmCapacity = min(2u * exactCounts[p], uint(dsmCompress.w));
  dsmCount = 0u;
  dsmCut = false;
  float eps = dsmCompress.x, t = dsmCompress.y;
  DsmEmit e;
  DsmState s;
  float v = 1.0;
  uint i = 0u;
  bool started = false;
  while (i < n) {
    // The fragments at one depth drop the visibility together.
    uint bits = exactNode(base + i).x;
    float before = v;
    while (i < n && exactNode(base + i).x == bits) {
      v *= t;
      ++i;
    }
    float z = uintBitsToFloat(bits);
    if (!started) s = dsmStart(z, v, eps, e);
    else dsmFeed(s, z, before, v, eps, e);
    started = true;
    dsmKeep(e);
  }
  if (n > 0u) {
    dsmFinish(s, e);
    dsmKeep(e);
  }
  dsmKept[p] = dsmCount;
  if (dsmCut) atomicAdd(dsmTruncated, 1u);
}
