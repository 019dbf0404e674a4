// Moment shadow maps, light pass: every hair fragment adds its absorbance to
// b0 and its absorbance times its moments of depth to the moment targets
// (additive blending; mboit_math.glsl).
#include "../mboit/mboit_math.glsl"
#include "msm.glsl"

layout(location = 0) in vec3 vWorldPos;

layout(location = 0) out vec4 outB0;
layout(location = 1) out vec4 outLow;
#ifdef SB_MSM_HIGH
layout(location = 2) out vec4 outHigh;
#endif

void main() {
  precise float z = msmDepth(msmLightDepth(vWorldPos));
  float a = mboitAbsorbance(msmParams.z);
  outB0 = vec4(a, 0.0, 0.0, 0.0);
  outLow = a * mboitMomentsLow(msmN.y, z);
#ifdef SB_MSM_HIGH
  outHigh = a * mboitMomentsHigh(msmN.y, z);
  if (msmN.x == 6) outHigh.zw = vec2(0.0);  // b5, b6 (or t3) only
#endif
}
