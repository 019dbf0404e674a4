// Eye-space A-buffer: every hair fragment in front of the opaque depth is
// shaded and stored in its pixel's list.
// Storage writes are side effects: without early tests they would happen even
// for fragments the opaque depth test then rejects.
layout(early_fragment_tests) in;
#include "render/common/view.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "render/common/fragment_key.glsl"
#include "abuffer.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;

void main() {
  uint p = pixelIndex(viewViewport.x);
  uint i = atomicAdd(cursor[p], 1u);
  if (i >= counts[p]) {  // over the pixel's capacity: reported, never silent
    atomicOr(overflow, 1u);
    atomicAdd(dropped, 1u);
    return;
  }
  setFragment(offsets[p] + i, Fragment(vec4(shadeHair(vWorldPos, vTangent, vColor.rgb), vColor.a),
                                       uvec4(fragmentKey(), 0u, 0u)));
}
