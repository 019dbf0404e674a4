// The current view (binding 0): camera or light. Kept apart from the scene's
// storage buffers because GL counts every std430 block a fragment shader
// declares against its limit (16 on llvmpipe), used or not.
#include "light_space.glsl"
#include "slots.h"
layout(std140, binding = SB_SLOT_VIEW) uniform View {
  mat4 viewProj;
  vec4 viewEye;       // xyz position; w: 1 perspective, 0 orthographic
  vec4 viewForward;   // view direction (orthographic views)
  vec4 viewViewport;  // width, height, ribbon width in pixels, 0
};

// viewProj * (p, 1) as clipOf computes it: the same bits on both APIs.
vec4 toViewClip(vec3 p) { return clipOf(viewProj, p); }
