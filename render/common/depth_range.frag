// Depth-range map: the nearest and furthest hair fragment of each light texel
// in one pass, min blending of (z, -z) into an RG32F target (occupancy maps;
// density clustering spreads its initial cluster centres over this range).
// From the light the depths are light distances (light_pass_depth.glsl).
#include "light_pass_depth.glsl"

layout(location = 0) out vec4 outRange;

void main() {
  float z = passDepth();
  outRange = vec4(z, -z, 0.0, 0.0);
}
