// Stochastic transparency, depth pass: the fragment covers each of the S
// samples with probability alpha (stochastic_math.glsl), keyed by its pixel,
// its primitive, the 32-sample word and the seed; each covered sample keeps
// the nearest depth (atomicMin). Storage writes are side effects: early tests
// keep hair behind the opaque depth out of them.
layout(early_fragment_tests) in;
#include "render/common/view.glsl"
#include "render/common/fragment_key.glsl"
#include "stochastic_pass.glsl"
#include "stochastic_math.glsl"

layout(location = 2) in vec4 vColor;

void main() {
  uint samples = stochParams.y;
  uint base = pixelIndex(viewViewport.x) * samples;
  uint depth = floatBitsToUint(gl_FragCoord.z);
  uvec2 p = uvec2(gl_FragCoord.xy);
  for (uint word = 0u; word * 32u < samples; ++word) {
    uint n = min(32u, samples - word * 32u);
    uint mask = stochasticMask(stochasticKey(p.x, p.y, uint(gl_PrimitiveID), word, stochParams.x),
                               vColor.a, n);
    for (uint k = 0u; k < n; ++k)
      if ((mask & (1u << k)) != 0u) atomicMin(stochDepths[base + word * 32u + k], depth);
  }
}
