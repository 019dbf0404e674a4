// Sorts each pixel's fragments front to back and composites them, with the
// same arithmetic as depth peeling.
#include "render/common/key_order.glsl"
#include "abuffer.glsl"
#include "render/common/invocation.glsl"
#include "render/common/slots.h"
layout(local_size_x = 64) in;
#include "uniforms.h"

void main() {
  uint p = linearInvocation();
  if (p >= size.x) return;
  uint base = offsets[p];
  uint n = min(cursor[p], counts[p]);
  for (uint i = 1u; i < n; ++i) {
    Fragment f = fragmentAt(base + i);
    uint j = i;
    while (j > 0u && keyLess(f.key.xy, fragmentAt(base + j - 1u).key.xy)) {
      setFragment(base + j, fragmentAt(base + j - 1u));
      --j;
    }
    setFragment(base + j, f);
  }
  vec4 acc = vec4(0.0);
  for (uint i = 0u; i < n; ++i) {
    Fragment f = fragmentAt(base + i);
    acc = acc + (1.0 - acc.a) * vec4(f.color.rgb * f.color.a, f.color.a);
  }
  accum[p] = acc;
}
