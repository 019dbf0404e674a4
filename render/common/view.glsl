// The current view (binding 0): camera or light. Kept apart from the scene's
// storage buffers because GL counts every std430 block a fragment shader
// declares against its limit (16 on llvmpipe), used or not.
#include "light_space.glsl"
#include "slots.h"
#include "view_uniforms.h"

// viewProj * (p, 1) as clipOf computes it: the same bits on both APIs.
vec4 toViewClip(vec3 p) { return clipOf(viewProj, p); }
