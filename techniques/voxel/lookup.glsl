// Voxelized hair density lookup: the hair count marched from the point
// towards the light through the grid (voxel_math.glsl), normalised to
// fragments per map texel; 0 behind the opaque mesh.
#include "../common/opaque_shadow.glsl"
#include "voxel.glsl"
int voxelColumns;
#define SB_VOXEL_COUNT(x, y, s) float(voxelCounts[((s)*voxelColumns + (y)) * voxelColumns + (x)])
#include "voxel_math.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(voxelViewProj, worldPos, ndc)) return 1.0;
  if (opaqueVisibility(ndc, voxelParams.x) == 0.0) return 0.0;
  voxelColumns = int(voxelCells.x);
  vec2 cell = (ndc.xy * 0.5 + 0.5) * voxelCells.x - 0.5;
  float u = voxelDepth(ndc.z - voxelParams.x);
  float n = voxelHairCount(cell.x, cell.y, u, voxelColumns, int(voxelCells.y), int(voxelRange.z));
  // A voxel's count over the (size / columns)^2 map texels of its column.
  float perTexel = voxelCells.x / voxelParams.y;
  return voxelVisibility(n * perTexel * perTexel, voxelParams.z, voxelParams.w);
}
