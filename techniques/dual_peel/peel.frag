// Dual depth peeling (Bavoil & Myers 2008). SB_DUAL_INIT: every visible
// fragment writes (-z, z) (MAX blending: the nearest and farthest depth) and
// zero front colour. SB_DUAL_PEEL: against the last pass's (-nearest,
// farthest) and front accumulation, with MAX blending on all three targets:
// outside [nearest, farthest] (peeled before): carry the front forward;
// inside: (-z, z) for the next pass; at nearest: blend under the front; at
// farthest: the back layer's (c, a).
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "slots.h"

layout(binding = SB_SLOT_DUAL_OPAQUE_DEPTH) uniform sampler2D dualOpaqueDepth;
#ifdef SB_DUAL_PEEL
layout(binding = SB_SLOT_DUAL_DEPTH) uniform sampler2D dualDepth;
layout(binding = SB_SLOT_DUAL_FRONT) uniform sampler2D dualFront;
#endif

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outDepth;
layout(location = 1) out vec4 outFront;
#ifdef SB_DUAL_PEEL
layout(location = 2) out vec4 outBack;
#endif

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = gl_FragCoord.z;
  if (z >= texelFetch(dualOpaqueDepth, p, 0).r) discard;  // behind the opaque surface
#ifdef SB_DUAL_INIT
  outDepth = vec4(-z, z, 0.0, 0.0);
  outFront = vec4(0.0);
#else
  vec2 range = texelFetch(dualDepth, p, 0).xy;
  float nearest = -range.x, farthest = range.y;
  vec4 front = texelFetch(dualFront, p, 0);
  outDepth = vec4(-1.0, -1.0, 0.0, 0.0);  // the MAX identity here (depths are in [0, 1])
  outFront = front;
  outBack = vec4(0.0);
  if (z < nearest || z > farthest) return;  // peeled by an earlier pass
  if (z > nearest && z < farthest) {        // a later pass peels it
    outDepth = vec4(-z, z, 0.0, 0.0);
    return;
  }
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  float a = vColor.a;
  if (z == nearest)
    outFront = front + (1.0 - front.a) * vec4(c * a, a);
  else
    outBack = vec4(c, a);
#endif
}
