// kbuffer resolve: each pixel's list, in submission order, through the
// k-buffer of kbuffer_math.glsl (SB_KBUFFER_K entries), into the accumulation.
#define SB_INOUT(T) inout T
#include "render/common/key_order.glsl"
#include "../abuffer/abuffer.glsl"
#include "../abuffer/submission_order.glsl"
#include "render/common/invocation.glsl"
#include "render/common/slots.h"
#define SB_KBUFFER_MAX SB_KBUFFER_K
#include "kbuffer_math.glsl"
layout(local_size_x = 64) in;
#include "../abuffer/uniforms.h"

void main() {
  uint p = linearInvocation();
  if (p >= size.x) return;
  uint base = offsets[p];
  uint n = min(cursor[p], counts[p]);
  sortBySubmission(base, n);
  KBuffer kb = kbufferEmpty();
  for (uint i = 0u; i < n; ++i) {
    Fragment f = fragmentAt(base + i);
    kbufferInsert(kb, SB_KBUFFER_K, f.color, f.key.xy);
  }
  accum[p] = kbufferResolve(kb);
}
