// Sorts each texel's fragment keys (insertion sort: lists are short on
// average, and any length works). By depth (the exact visibility), or with
// SB_EXACT_BY_SUBMISSION by primitive id then depth: the order ordered
// interlock processes fragments in, for a streaming resolve (avsm).
#include "render/common/key_order.glsl"
#include "exact.glsl"
#include "render/common/invocation.glsl"
layout(local_size_x = 64) in;
#ifdef SB_EXACT_BY_SUBMISSION
#define SB_EXACT_ORDER(k) (k).yx
#else
#define SB_EXACT_ORDER(k) (k)
#endif

void main() {
  uint size = uint(exactParams.y);
  uint p = linearInvocation();
  if (p >= size * size) return;
  uint base = exactOffsets[p];
  uint n = min(exactCursor[p], exactCounts[p]);
  for (uint i = 1u; i < n; ++i) {
    uvec2 key = exactNode(base + i);
    uint j = i;
    while (j > 0u && keyLess(SB_EXACT_ORDER(key), SB_EXACT_ORDER(exactNode(base + j - 1u)))) {
      setExactNode(base + j, exactNode(base + j - 1u));
      --j;
    }
    setExactNode(base + j, key);
  }
}
