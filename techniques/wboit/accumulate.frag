// Weighted blended OIT accumulation (McGuire & Bavoil 2013): target 0 adds
// (c a w, a w) (additive), target 1 (R32F revealage, cleared to 1) multiplies by
// (1 - a) (blend Zero, OneMinusSrcColor). z for the weight is the view-space
// depth: the interpolated world position projected on the camera's forward axis.
#include "render/common/view.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "wboit_math.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outAccum;
layout(location = 1) out vec4 outRevealage;

void main() {
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  float a = vColor.a;
  float z = dot(vWorldPos - viewEye.xyz, viewForward.xyz);
  float w = wboitWeight(SB_WBOIT_WEIGHT, z, gl_FragCoord.z, a);
  outAccum = vec4(c * a, a) * w;
  outRevealage = vec4(a);
}
