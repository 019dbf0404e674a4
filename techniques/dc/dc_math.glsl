// Density clustering (Mertens et al. 2004): per light texel, the hair
// fragments' depths are grouped by k-means into up to 8 clusters (the
// functions below take them 4 at a time, an RGBA layer); a cluster
// is its fragment count n, mean depth m and standard deviation sd, and its
// fragments are taken as spread uniformly over [m - sqrt(3) sd, m + sqrt(3) sd]
// (the uniform distribution with that deviation), so the count in front of a
// depth, and the opacity, grows linearly across each cluster. Pure math,
// compiled as GLSL and, through dc_math.h, as C++ with GLM for CPU tests.
//
// Depths are relative to the texel's nearest fragment (zMin) so that the sums
// of squares keep their precision in 32-bit floats: a cluster is stored as
// (n, s1, s2) = (count, sum of (z - zMin), sum of (z - zMin)^2).
#ifndef SB_INLINE
#define SB_INLINE
#endif

// Initial centre of cluster j of k: spread evenly over [zMin, zMax].
SB_INLINE float dcInitialCentre(int j, int k, float zMin, float zMax) {
  float range = max(zMax - zMin, 0.0f);
  return zMin + (float(j) + 0.5f) / float(k) * range;
}

// The cluster with the nearest centre (ties: the lower index).
SB_INLINE int dcNearest(float z, vec4 centres, int k) {
  int best = 0;
  float bestDistance = abs(z - centres[0]);
  for (int j = 1; j < k; ++j) {
    float d = abs(z - centres[j]);
    if (d < bestDistance) {
      bestDistance = d;
      best = j;
    }
  }
  return best;
}

// New centre of a cluster from its sums; an empty cluster keeps `fallback`.
SB_INLINE float dcCentre(float n, float s1, float zMin, float fallback) {
  return n > 0.0f ? zMin + s1 / n : fallback;
}

// Fragments of one cluster in front of depth zRel (relative to zMin).
SB_INLINE float dcClusterCount(float zRel, float n, float s1, float s2) {
  if (!(n > 0.0f)) return 0.0f;
  float mean = s1 / n;
  float sd = sqrt(max(s2 / n - mean * mean, 0.0f));
  float halfWidth = 1.7320508f * sd;  // sqrt(3) sd
  float lo = mean - halfWidth;
  float hi = mean + halfWidth;
  if (zRel <= lo) return 0.0f;
  if (zRel >= hi) return n;  // also a zero-width cluster with zRel beyond its mean
  return n * clamp((zRel - lo) / (hi - lo), 0.0f, 1.0f);
}

// Fragments of all k clusters in front of depth z.
SB_INLINE float dcCount(float z, float zMin, float zMax, vec4 n, vec4 s1, vec4 s2, int k) {
  if (zMax < zMin) return 0.0f;  // no fragment in this texel
  float count = 0.0f;
  for (int j = 0; j < k; ++j) count += dcClusterCount(z - zMin, n[j], s1[j], s2[j]);
  return count;
}

// (1 - alpha_s)^n, with no fragment in front fully lit (pow(0, 0) is undefined).
SB_INLINE float dcVisibility(float n, float alpha) {
  if (!(n > 0.0f)) return 1.0f;
  return clamp(pow(clamp(1.0f - alpha, 0.0f, 1.0f), n), 0.0f, 1.0f);
}
