// One opacity-map pass: every hair fragment adds its weight to each map of
// this pass whose depth D_i lies behind it (equivalent to the paper's render
// of slab [D_(i-1), D_i) added to the previous map, since addition commutes).
// Fragments outside this pass's atlas tile are discarded.
#include "osm.glsl"
#include "render/common/light_space.glsl"
#include "slots.h"

#include "pass_uniforms.h"

// Target k is layer k of the atlas array. One output per target, written by
// name: llvmpipe runs this pass about 20% slower when an output array is
// filled in a loop (osm:maps=16 at 128x128: 22.6 vs 18.2 ms; DOM's loop
// shows no difference).
layout(location = 0) out vec4 osmOut0;
#if SB_OSM_TARGETS > 1
layout(location = 1) out vec4 osmOut1;
#endif
#if SB_OSM_TARGETS > 2
layout(location = 2) out vec4 osmOut2;
#endif
#if SB_OSM_TARGETS > 3
layout(location = 3) out vec4 osmOut3;
#endif
#if SB_OSM_TARGETS > 4
layout(location = 4) out vec4 osmOut4;
#endif
#if SB_OSM_TARGETS > 5
layout(location = 5) out vec4 osmOut5;
#endif

vec4 osmTarget(int k, float z) {
  vec4 o = vec4(0.0);
  for (int c = 0; c < 4; ++c) {
    int m = 4 * (osmPass.x + k) + c;  // map m + 1, depth D_(m+1)
    if (m >= osmPass.y && m < osmPass.z && z < SB_LAYER_BOUND(m + 1)) o[c] = osmParams.w;
  }
  return o;
}

void main() {
  vec2 p = gl_FragCoord.xy;
  if (p.x < osmTile.x || p.y < osmTile.y || p.x >= osmTile.z || p.y >= osmTile.w) discard;
  float z = lightDistance(osmViewProj, gl_FragCoord.z);  // linear for point lights
  osmOut0 = osmTarget(0, z);
#if SB_OSM_TARGETS > 1
  osmOut1 = osmTarget(1, z);
#endif
#if SB_OSM_TARGETS > 2
  osmOut2 = osmTarget(2, z);
#endif
#if SB_OSM_TARGETS > 3
  osmOut3 = osmTarget(3, z);
#endif
#if SB_OSM_TARGETS > 4
  osmOut4 = osmTarget(4, z);
#endif
#if SB_OSM_TARGETS > 5
  osmOut5 = osmTarget(5, z);
#endif
}
