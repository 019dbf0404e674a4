// The current view (binding 0): camera or light. Kept apart from the scene's
// storage buffers because GL counts every std430 block a fragment shader
// declares against its limit (16 on llvmpipe), used or not.
#include "slots.h"
layout(std140, binding = SB_SLOT_VIEW) uniform View {
  mat4 viewProj;
  vec4 viewEye;       // xyz position; w: 1 perspective, 0 orthographic
  vec4 viewForward;   // view direction (orthographic views)
  vec4 viewViewport;  // width, height, ribbon width in pixels, 0
};

// viewProj * (p, 1), the sums in one written order and `precise` (no fused
// multiply-adds): GL's GLSL compiler and glslang's SPIR-V otherwise round the
// product differently in the last bit, and the rasterizers then interpolate
// every attribute (and gl_FragCoord.z) 1-2 ulp apart between the APIs, which
// moment shadow maps amplify (MomentShadowsParity in tests/test_moments.cpp).
vec4 toViewClip(vec3 p) {
  precise vec4 c = ((viewProj[0] * p.x + viewProj[1] * p.y) + viewProj[2] * p.z) + viewProj[3];
  return c;
}
