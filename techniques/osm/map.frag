// One opacity-map pass: every hair fragment adds its weight to each map of
// this pass whose depth D_i lies behind it (equivalent to the paper's render
// of slab [D_(i-1), D_i) added to the previous map, since addition commutes).
// Fragments outside this pass's atlas tile are discarded.
#include "osm.glsl"

layout(std140, binding = 9) uniform OsmPass {
  ivec4 osmPass;  // first texel group of target 0, first map, end map, 0
  vec4 osmTile;   // the tile's pixel rectangle x0, y0, x1, y1
};

// Target k is layer k of the atlas array.
layout(location = 0) out vec4 osmOut[SB_OSM_TARGETS];

vec4 osmTarget(int k, float z) {
  vec4 o = vec4(0.0);
  for (int c = 0; c < 4; ++c) {
    int m = 4 * (osmPass.x + k) + c;  // map m + 1, depth D_(m+1)
    if (m >= osmPass.y && m < osmPass.z && z < SB_OSM_SLICE(m + 1)) o[c] = osmParams.w;
  }
  return o;
}

void main() {
  vec2 p = gl_FragCoord.xy;
  if (p.x < osmTile.x || p.y < osmTile.y || p.x >= osmTile.z || p.y >= osmTile.w) discard;
  float z = gl_FragCoord.z;
  for (int k = 0; k < SB_OSM_TARGETS; ++k) osmOut[k] = osmTarget(k, z);
}
