// mlab without fragment-shader interlock: each pixel's fragments merged in
// submission order (the order ordered interlock guarantees), so the image is
// the one the paper's single geometry pass would give; the cost is not.
// status.resolveCounter counts the fragments merged (the emulated steps).
#define SB_INOUT(T) inout T
#include "render/common/key_order.glsl"
#include "../abuffer/abuffer.glsl"
#include "../abuffer/submission_order.glsl"
#include "render/common/invocation.glsl"
#include "render/common/slots.h"
#define SB_MLAB_MAX SB_MLAB_LAYERS
#include "mlab_math.glsl"
layout(local_size_x = 64) in;
#include "../abuffer/uniforms.h"

void main() {
  uint p = linearInvocation();
  if (p >= size.x) return;
  uint base = offsets[p];
  uint n = min(cursor[p], counts[p]);
  sortBySubmission(base, n);
  MlabLayers m = mlabEmpty();
  for (uint i = 0u; i < n; ++i) {
    Fragment f = fragmentAt(base + i);
    mlabInsert(m, SB_MLAB_LAYERS, f.color, f.key.xy);
  }
  accum[p] = mlabResolve(m);
  if (n > 0u) atomicAdd(resolveCounter, n);
}
