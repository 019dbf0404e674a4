// Stochastic transparency, accumulation: every hair fragment adds (a c, a)
// to the samples where it is not behind the stochastic depth (test LessEqual,
// no write); the pass's resolve averages the samples, so the fragment counts
// with the fraction it passed: its estimated visibility prod(1 - a_j).
#include "../common/shading.glsl"
#include <shadow>
#include "../kajiya_kay/hair_shading.glsl"
#include "stochastic_pass.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outAccum;

void main() {
  if (behindOpaque()) discard;
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  outAccum = vec4(c * vColor.a, vColor.a);
}
