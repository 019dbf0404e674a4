// Weighted sum / weighted average accumulation (Bavoil & Myers 2008): every
// visible hair fragment adds (a c, a) to target 0 (additive blending, RGBA32F);
// SB_WEIGHTED_COUNT also adds 1 to target 1 (R32F), the fragment count n.
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outAccum;
#ifdef SB_WEIGHTED_COUNT
layout(location = 1) out vec4 outCount;
#endif

void main() {
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  float a = vColor.a;
  outAccum = vec4(c * a, a);
#ifdef SB_WEIGHTED_COUNT
  outCount = vec4(1.0);
#endif
}
