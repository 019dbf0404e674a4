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
// the density at the step's middle in the point's own column (the column
// holding the light ray, as the other maps look up their texel), linear
// between slice centres. The partial step takes the density
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
// Hair count per slice in column (x, y) at normalised depth u: linear between
// slice centres, constant beyond the first and the last.
SB_INLINE float voxelDensity(int x, int y, float u, int gz) {
  float cz = u * float(gz) - 0.5f;
  float fz = floor(cz);
  float wz = cz - fz;
  int z0 = clamp(int(fz), 0, gz - 1), z1 = clamp(int(fz) + 1, 0, gz - 1);
  return (1.0f - wz) * SB_VOXEL_COUNT(x, y, z0) + wz * SB_VOXEL_COUNT(x, y, z1);
}

// The hair count in column (x, y) in front of normalised depth u (the march,
// from the receiver towards the light), in stored counts; the caller
// normalises it.
SB_INLINE float voxelHairCount(int x, int y, float u, int gz, int steps) {
  u = clamp(u, 0.0f, 1.0f);
  float h = 1.0f / float(steps);
  int k = min(int(floor(u / h)), steps - 1);
  // A count per slice times gz is a density per unit u.
  float perU = float(gz);
  float n = (u - float(k) * h) * perU * voxelDensity(x, y, (float(k) + 0.5f) * h, gz);
  for (int i = k - 1; i >= 0; --i) n += h * perU * voxelDensity(x, y, (float(i) + 0.5f) * h, gz);
  return n;
}
#endif

// exp(-density_scale w n), w = -ln(1 - alpha), in [0, 1].
SB_INLINE float voxelVisibility(float hairCount, float alphaS, float densityScale) {
  float w = -log(1.0f - clamp(alphaS, 0.0f, 0.999999f));
  return clamp(exp(-densityScale * w * max(hairCount, 0.0f)), 0.0f, 1.0f);
}
