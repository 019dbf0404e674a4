// Voxelized hair density (as Unreal's hair strands voxelization ships it, and
// vkhr's density volume): a volume of hair fragment counts over the light's
// view (x, y: gx columns per side over the light map's texels; z: gz slices
// over the hair's depth range from the light), and a point's visibility from
// the hair count marched from it towards the light,
//   n(u) = integral from 0 to u of rho,  V = exp(-density_scale w n(u)),
// w = -ln(1 - alpha) the absorption of one fragment: with density_scale 1
// and the exact count, V is the exact (1 - alpha)^n. This is the
// exponential (Beer-Lambert) form over the marched hair count. Unreal marches
// its voxelized hair density towards the light as we do, but turns the hair
// count into transmittance through its hair BSDF's lookup table
// (HairStrandsTransmittance), which needs a scattering model this shadow
// comparison does not have; vkhr's volume accumulates density along rays
// (volume_rendering.glsl) for its raymarched level of detail.
// Where the volume loses accuracy: each voxel averages the fragment count
// over (size / gx)^2 map texels and 1 / gz of the depth range, and the march
// samples the density at `steps` points.
//
// The march: the depth range u in [0, 1] is cut into `steps` steps of length
// h = 1 / steps on a fixed lattice; from the receiver towards the light, the
// partial step it lies in, then every full step, each adding its length times
// the density at the step's middle (trilinear: bilinear across the voxel
// columns, linear between slice centres). The partial step takes the density
// of the middle of the full step it lies in, so n(u) is continuous and never
// falls as u grows (the density is never negative): the visibility never
// rises away from the light (promised, and checked by --invariants).
//
// SB_VOXEL_COUNT(x, y, s): the stored count of voxel (column x, y, slice s), as float.
// Pure math, compiled as GLSL and, through voxel_math.h, as C++ for CPU tests.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#ifdef SB_VOXEL_COUNT
// Hair count per slice at grid cell coordinates (cx, cy) (continuous, voxel
// centres at integers) and normalised depth u: trilinear, clamped to the grid.
SB_INLINE float voxelDensity(float cx, float cy, float u, int gx, int gz) {
  float cz = u * float(gz) - 0.5f;
  float fx = floor(cx), fy = floor(cy), fz = floor(cz);
  float wx = cx - fx, wy = cy - fy, wz = cz - fz;
  float sum = 0.0f;
  for (int k = 0; k < 8; ++k) {
    int dx = k & 1, dy = (k >> 1) & 1, dz = (k >> 2) & 1;
    int x = clamp(int(fx) + dx, 0, gx - 1), y = clamp(int(fy) + dy, 0, gx - 1),
        z = clamp(int(fz) + dz, 0, gz - 1);
    float w = (dx == 1 ? wx : 1.0f - wx) * (dy == 1 ? wy : 1.0f - wy) *
              (dz == 1 ? wz : 1.0f - wz);
    if (w > 0.0f) sum += w * SB_VOXEL_COUNT(x, y, z);
  }
  return sum;
}

// The hair count in front of normalised depth u (the march, from the
// receiver towards the light), in stored counts; the caller normalises it.
SB_INLINE float voxelHairCount(float cx, float cy, float u, int gx, int gz, int steps) {
  u = clamp(u, 0.0f, 1.0f);
  float h = 1.0f / float(steps);
  int k = min(int(floor(u / h)), steps - 1);
  // A count per slice times gz is a density per unit u.
  float perU = float(gz);
  float n = (u - float(k) * h) * perU * voxelDensity(cx, cy, (float(k) + 0.5f) * h, gx, gz);
  for (int i = k - 1; i >= 0; --i)
    n += h * perU * voxelDensity(cx, cy, (float(i) + 0.5f) * h, gx, gz);
  return n;
}
#endif

// exp(-density_scale w n), w = -ln(1 - alpha), in [0, 1].
SB_INLINE float voxelVisibility(float hairCount, float alphaS, float densityScale) {
  float w = -log(1.0f - clamp(alphaS, 0.0f, 0.999999f));
  return clamp(exp(-densityScale * w * max(hairCount, 0.0f)), 0.0f, 1.0f);
}
