// Every hair fragment from the light (at the splat size) adds 1 to its voxel:
// the map texel's column of the grid, the slice of its depth.
#include "voxel.glsl"

void main() {
  int g = int(voxelCells.x), slices = int(voxelCells.y);
  float scale = float(g) / voxelParams.y;
  ivec2 c = min(ivec2((floor(gl_FragCoord.xy) + 0.5) * scale), ivec2(g - 1));
  int s = clamp(int(floor(voxelDepth(gl_FragCoord.z) * float(slices))), 0, slices - 1);
  atomicAdd(voxelCounts[(s * g + c.y) * g + c.x], 1u);
}
