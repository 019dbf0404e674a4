// The opaque mesh's hard shadow, shared by every shadow technique: a depth
// map of the mesh from the light (binding 15). Compiled out (SB_OPAQUE_SHADOW 0)
// when the scene has no mesh, so such a scene allocates and runs nothing for it.
#include "light_space.glsl"
#include "slots.h"
#if SB_OPAQUE_SHADOW
layout(binding = SB_SLOT_OPAQUE_SHADOW) uniform sampler2D opaqueShadowDepth;
#endif

// ndc: the point in the light's normalized device coordinates, inside the map.
float opaqueVisibility(vec3 ndc, float bias) {
#if SB_OPAQUE_SHADOW
  return ndc.z - bias > textureLod(opaqueShadowDepth, ndc.xy * 0.5 + 0.5, 0.0).r ? 0.0 : 1.0;
#else
  return 1.0;
#endif
}
