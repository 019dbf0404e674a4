// Classic depth peeling (Everitt 2001), one layer: a fragment strictly behind
// the previous layer's depth (the "second depth test", against the R32F copy
// of the last pass) and in front of the opaque surface writes its shaded,
// premultiplied colour and its depth; the depth test (Less) keeps the nearest.
// A fragment at exactly a peeled depth fails the strict test: ties are lost.
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "slots.h"

layout(binding = SB_SLOT_PEELC_PREV_DEPTH) uniform sampler2D peelPrevDepth;
layout(binding = SB_SLOT_PEELC_OPAQUE_DEPTH) uniform sampler2D peelOpaqueDepth;

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outDepth;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = gl_FragCoord.z;
  if (z <= texelFetch(peelPrevDepth, p, 0).r) discard;
  if (z >= texelFetch(peelOpaqueDepth, p, 0).r) discard;
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  outColor = vec4(c * vColor.a, vColor.a);
  outDepth = vec4(z);
}
