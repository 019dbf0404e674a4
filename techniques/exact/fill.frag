// Light-space A-buffer: every hair fragment appends its key to its texel's list.
#include "render/common/view.glsl"
#include "render/common/fragment_key.glsl"
#include "exact.glsl"

void main() {
  uint p = pixelIndex(exactParams.y);
  uint i = atomicAdd(exactCursor[p], 1u);
  if (i >= exactCounts[p]) {  // more fragments than counted: reported, never silent
    atomicOr(exactOverflow, 1u);
    return;
  }
  setExactNode(exactOffsets[p] + i, fragmentKey());
}
