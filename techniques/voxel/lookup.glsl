// Voxelized hair density lookup: the hair count marched from the point
// towards the light through the grid (voxel_math.glsl), normalised to
// fragments per map texel; 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "voxel.glsl"
int voxelColumns;
#define SB_VOXEL_COUNT(x, y, s) float(voxelCounts[((s)*voxelColumns + (y)) * voxelColumns + (x)])
#include "voxel_math.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(voxelViewProj, worldPos, ndc)) return 1.0;
  if (opaqueVisibility(ndc, voxelParams.x) == 0.0) return 0.0;
  voxelColumns = int(voxelCells.x);
  // The column of the point's map texel (as splat.frag assigns texels).
  int size = int(voxelParams.y);
  ivec2 texel = min(ivec2((ndc.xy * 0.5 + 0.5) * voxelParams.y), ivec2(size - 1));
  ivec2 col = min(ivec2((vec2(texel) + 0.5) * (voxelCells.x / voxelParams.y)), ivec2(voxelColumns - 1));
  float u = voxelDepth(ndc.z - voxelParams.x);
  float n = voxelHairCount(col.x, col.y, u, int(voxelCells.y), int(voxelRange.z));
  // A voxel's count over the (size / columns)^2 map texels of its column.
  float perTexel = voxelCells.x / voxelParams.y;
  return voxelVisibility(n * perTexel * perTexel, voxelParams.z, voxelParams.w);
}
