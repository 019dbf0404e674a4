// Stochastic transparency, depth pass: the fragment covers each of the m
// samples with probability alpha (stochastic_math.glsl), keyed by its pixel,
// its primitive, the pass group and the seed; the multisampled depth test
// (Less, write) keeps the nearest covering depth per sample.
#include "stochastic_pass.glsl"
#include "stochastic_math.glsl"

layout(location = 2) in vec4 vColor;

void main() {
  if (behindOpaque()) discard;
  uvec2 p = uvec2(gl_FragCoord.xy);
  uint key = stochasticKey(p.x, p.y, uint(gl_PrimitiveID), stochParams.y, stochParams.x);
  uint mask = stochasticMask(key, vColor.a, stochParams.z);
  if (mask == 0u) discard;
  gl_SampleMask[0] = int(mask);
}
