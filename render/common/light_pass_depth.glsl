// The depth a hair fragment of a map pass is placed by: with
// SB_LIGHT_DISTANCE (the shadow techniques' passes from the light) its
// lightDistance (light_space.glsl: linear in distance for a point light), else
// its window depth (e.g. occupancy-ordered blending's maps from the eye).
#include "light_space.glsl"
#include "view.glsl"

float passDepth() {
#ifdef SB_LIGHT_DISTANCE
  return lightDistance(viewProj, gl_FragCoord.z);
#else
  return gl_FragCoord.z;
#endif
}
