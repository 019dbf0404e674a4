// Stochastic transparency, accumulation: every hair fragment adds (a c, a)
// times the fraction of the S samples where it is not behind the stochastic
// depth (its own covered samples hold its depth: <= passes), its estimated
// visibility prod(1 - a_j) (additive blending into one RGBA32F target).
layout(early_fragment_tests) in;
#include "render/common/view.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "render/common/fragment_key.glsl"
#include "stochastic_pass.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outAccum;

void main() {
  uint samples = stochParams.y;
  uint base = pixelIndex(viewViewport.x) * samples;
  uint depth = floatBitsToUint(gl_FragCoord.z);
  uint passed = 0u;
  for (uint k = 0u; k < samples; ++k) passed += depth <= stochDepths[base + k] ? 1u : 0u;
  float visibility = float(passed) / float(samples);
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  outAccum = vec4(c * vColor.a, vColor.a) * visibility;
}
