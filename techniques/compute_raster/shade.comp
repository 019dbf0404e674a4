// compute_raster with shading=point: each segment's two ends shaded once (the
// shading model through the shadow technique's lookup, with the segment's
// tangent, as the hardware techniques' vertex shader gives every fragment of
// it); the resolve interpolates them along the segment.
#include "render/common/bindings.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "render/common/invocation.glsl"
#include "slots.h"
#include "uniforms.h"
layout(local_size_x = 64) in;
layout(std430, binding = SB_SLOT_CRASTER_SHADED) writeonly buffer Shaded { vec4 shaded[]; };

void main() {
  uint seg = linearInvocation();
  if (seg >= crModel.z) return;
  uint first = segments[seg];
  vec3 p0 = points[first].xyz, p1 = points[first + 1u].xyz;
  vec3 d = p1 - p0;
  vec3 tangent = dot(d, d) > 1e-30 ? normalize(d) : vec3(0.0, 1.0, 0.0);
  vec4 c0 = colors[first], c1 = colors[first + 1u];
  shaded[2u * seg] = vec4(shadeHair(p0, tangent, c0.rgb), c0.a);
  shaded[2u * seg + 1u] = vec4(shadeHair(p1, tangent, c1.rgb), c1.a);
}
