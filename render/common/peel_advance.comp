// After a peel layer: the key found becomes the previous key, the layer count
// grows, and the minimum is reset. STATE_BINDING / PEELED_BINDING (and the nodes'),
// from the C++; the size: PeelSize (peel_uniforms.h).
#include "invocation.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = STATE_BINDING) buffer PeelState { uvec4 peelState[]; };
layout(std430, binding = PEELED_BINDING) buffer Peeled { uint peeled[]; };
#ifdef NODES_BINDING
// Light-space peeling stores each layer's key in the texel's list.
layout(std430, binding = OFFSETS_BINDING) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = NODES_BINDING) buffer Nodes { uvec2 nodes[]; };
#endif
#include "peel_uniforms.h"

void main() {
  uint p = linearInvocation();
  if (p >= peelSize.x) return;
  uvec4 s = peelState[p];
  if (s.z == 0xFFFFFFFFu && s.w == 0xFFFFFFFFu) return;  // nothing left in this pixel
#ifdef NODES_BINDING
  nodes[offsets[p] + peeled[p]] = s.zw;
#endif
  peelState[p] = uvec4(s.zw, 0xFFFFFFFFu, 0xFFFFFFFFu);
  peeled[p] += 1u;
}
