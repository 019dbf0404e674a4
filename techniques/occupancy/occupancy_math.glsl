// Occupancy maps (Sintorn & Assarsson 2009): the visibility reconstruction
// from a texel's depth range, occupancy bits and slab counts. Pure math,
// compiled as GLSL and, through occupancy_math.h, as C++ with GLM so CPU tests
// check it on extreme inputs.
//
// A texel holds: its nearest and furthest hair fragment depth [zMin, zMax]
// (zMax < zMin: no fragment), `slices` occupancy bits (bit s set: at least one
// fragment in slice s of the range, 32 bits per word), and the fragment count
// F_i of each of `slabs` equal groups of slices. Following the paper, the
// fragments of slab i are spread evenly over its S_i set bits (F_i / S_i per
// set bit) and uniformly within a slice (linear interpolation inside it).
// Without the slab map every set bit counts as one fragment.
#ifndef SB_OCCUPANCY_MATH_GLSL  // included by the lookup and by occupancy blending
#define SB_OCCUPANCY_MATH_GLSL
#ifndef SB_INLINE
#define SB_INLINE
#endif

// The arrays below hold the words and slabs a pipeline uses (set from C++ by
// OccupancyMaps::defines(), the most of its users), else the most there can be.
// Sized to need: with 32 entries at 128 slices, lavapipe ran occupancy
// blending's accumulation about 1.5x slower (the arrays live in memory).
#ifndef SB_OCC_MAX_WORDS
#define SB_OCC_MAX_WORDS 32  // 1024 slices (OccupancyMaps::kMaxSlices)
#endif
#ifndef SB_OCC_MAX_SLABS
#define SB_OCC_MAX_SLABS 32  // OccupancyMaps::kMaxSlabs
#endif

// The slice a fragment at depth z falls in (the occupancy and slab passes).
SB_INLINE int occupancySlice(float z, float zMin, float zMax, int slices) {
  float range = zMax - zMin;
  float d = range > 0.0f ? clamp((z - zMin) / range, 0.0f, 1.0f) : 0.0f;
  return min(int(d * float(slices)), slices - 1);
}

// The number of set bits among slices [first, last).
SB_INLINE int occupancyBitsBetween(uint bits[SB_OCC_MAX_WORDS], int first, int last) {
  int n = 0;
  for (int w = first / 32; w * 32 < last; ++w) {
    int lo = max(first - w * 32, 0);
    int hi = min(last - w * 32, 32);
    // Bits lo..hi-1 of the word (hi - lo in 1..32).
    uint mask = (hi - lo == 32) ? 0xFFFFFFFFu : (((1u << uint(hi - lo)) - 1u) << uint(lo));
    n += bitCount(bits[w] & mask);
  }
  return n;
}

// Estimated number of hair fragments in front of depth z.
SB_INLINE float occupancyCount(float z, float zMin, float zMax, uint bits[SB_OCC_MAX_WORDS],
                               float slabCounts[SB_OCC_MAX_SLABS], int slices, int slabs,
                               bool useSlabs) {
  if (zMax < zMin || z <= zMin) return 0.0f;  // empty texel, or in front of every fragment
  float total = 0.0f;
  if (useSlabs) {
    for (int i = 0; i < slabs; ++i) total += slabCounts[i];
  } else {
    total = float(occupancyBitsBetween(bits, 0, slices));
  }
  float range = zMax - zMin;
  if (z > zMax || !(range > 0.0f)) return total;  // behind every fragment
  float t = (z - zMin) / range * float(slices);  // in slices, (0, slices]
  int s = min(int(t), slices - 1);
  float f = clamp(t - float(s), 0.0f, 1.0f);  // how far into slice s
  float own = (bits[s / 32] & (1u << uint(s % 32))) != 0u ? 1.0f : 0.0f;
  if (!useSlabs) return float(occupancyBitsBetween(bits, 0, s)) + f * own;
  int perSlab = slices / slabs;
  int slab = s / perSlab;
  int first = slab * perSlab;
  float before = 0.0f;
  for (int i = 0; i < slab; ++i) before += slabCounts[i];
  float fi = slabCounts[slab];
  int setTotal = occupancyBitsBetween(bits, first, first + perSlab);
  if (setTotal == 0) {
    // Fragments counted without a bit (cannot happen when both passes agree):
    // spread them over the whole slab.
    return before + fi * (float(s - first) + f) / float(perSlab);
  }
  float perBit = fi / float(setTotal);
  return before + perBit * (float(occupancyBitsBetween(bits, first, s)) + f * own);
}

// (1 - alpha_s)^n, with no fragment in front fully lit (pow(0, 0) is undefined).
SB_INLINE float occupancyVisibility(float n, float alpha) {
  if (!(n > 0.0f)) return 1.0f;
  return clamp(pow(clamp(1.0f - alpha, 0.0f, 1.0f), n), 0.0f, 1.0f);
}

#endif  // SB_OCCUPANCY_MATH_GLSL
