// mboit pass 2: every visible hair fragment adds (c a T, a T), T the
// transmittance in front of it reconstructed from the moments of pass 1.
#include "render/common/view.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "mboit.glsl"
#include "mboit_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_MBOIT_B0) uniform sampler2D b0Tex;
layout(binding = SB_SLOT_MBOIT_LOW) uniform sampler2D lowTex;
#ifdef SB_MBOIT_HIGH
layout(binding = SB_SLOT_MBOIT_HIGH) uniform sampler2D highTex;
#endif

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outAccum;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  precise float z =
      mboitWarpDepth(dot(vWorldPos - viewEye.xyz, viewForward.xyz), mboitWarp.x, mboitWarp.y);
  vec4 high = vec4(0.0);
#ifdef SB_MBOIT_HIGH
  high = texelFetch(highTex, p, 0);
#endif
  float t = mboitTransmittanceOf(mboitN.z, 2 * mboitN.x, texelFetch(b0Tex, p, 0).x,
                                 texelFetch(lowTex, p, 0), high, z, mboitWarp.z, mboitWarp.w);
  float a = vColor.a;
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  outAccum = vec4(c * a, a) * t;
}
