// mboit pass 1: every visible hair fragment adds its absorbance A to b0 and
// A z^k (power) or A e^(i k phi) (trigonometric) to the moment targets (additive blending; mboit_math.glsl).
#include "render/common/view.glsl"
#include "mboit.glsl"
#include "mboit_math.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outB0;
layout(location = 1) out vec4 outLow;
#ifdef SB_MBOIT_HIGH
layout(location = 2) out vec4 outHigh;
#endif

void main() {
  precise float z =
      mboitWarpDepth(dot(vWorldPos - viewEye.xyz, viewForward.xyz), mboitWarp.x, mboitWarp.y);
  float a = mboitAbsorbance(vColor.a);
  outB0 = vec4(a, 0.0, 0.0, 0.0);
  outLow = a * mboitMomentsLow(mboitN.z, z);
#ifdef SB_MBOIT_HIGH
  outHigh = a * mboitMomentsHigh(mboitN.z, z);
  if (mboitN.x == 3) outHigh.zw = vec2(0.0);  // 6 moments: b5, b6 (or t3) only
#endif
}
