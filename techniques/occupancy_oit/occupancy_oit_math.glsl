// Occupancy-ordered blending (Sintorn & Assarsson 2009, section 3.4): the pure
// math of the accumulation and resolve passes, compiled as GLSL and, through
// occupancy_oit_math.h, as C++ with GLM so CPU tests check it on extreme
// inputs. The order estimate builds on occupancyCount() (fragments in front,
// from the depth range, occupancy bits and slab counts) in
// techniques/occupancy/occupancy_math.glsl, shared with the shadow version;
// include that file first.
//
// Back-to-front "over" of n fragments with one alpha (paper, 3.4):
//   f = sum_{i=0}^{n-1} (1 - a)^i a c_{n-1-i} + (1 - a)^n b
// so a fragment of order o (o fragments in front of it) contributes
//   color_out = (1 - a)^o * a * color_in                      (additive, fp32)
// and the background is multiplied by (1 - a)^n. With color_in.a = 1 the
// alpha channel sums to an estimate of
//   Lambda = sum_{i=0}^{n-1} (1 - a)^i a = 1 - (1 - a)^n
// and the hair is renormalised so its total weight is exactly Lambda.
// Per-fragment alpha (the paper assumes one alpha per pixel): each fragment
// uses its own a_i in (1 - a_i)^o a_i, and the background is multiplied by
// prod (1 - a_i) = exp2(sum log2(1 - a_i)), which is (1 - a)^n when all a_i
// are equal; Lambda = 1 - prod (1 - a_i).
#ifndef SB_INLINE
#define SB_INLINE
#endif

// log2(1 - a), for a in [0, 1). For a < 1e-2 the series -(a + a^2/2 + a^3/3
// + a^4/4) / ln 2 avoids rounding 1 - a in fp32 (a = 1e-7 would lose about
// 1% of its log); the next term, a^5/5, is below fp32's relative precision.
SB_INLINE float oitLog2OneMinus(float a) {
  if (a < 1e-2f) return -a * (1.0f + a * (0.5f + a * (1.0f / 3.0f + a * 0.25f))) * 1.44269504f;
  return log2(1.0f - a);
}

// log2(1 - a) per fragment, summed additively per pixel. Clamped at -200: 2^-200
// is below the smallest fp32 denormal (2^-149), so a fully opaque fragment
// (a = 1) hides what is behind it without -inf entering the sum.
SB_INLINE float oitLog2Transmittance(float a) {
  if (!(a > 0.0f)) return 0.0f;
  return a < 1.0f ? max(oitLog2OneMinus(a), -200.0f) : -200.0f;
}

// (1 - a)^o as exp2(o * log2(1 - a)), finite for every input: 1 for o <= 0
// (pow(0, 0) = 1) and for a <= 0; 0 for a >= 1 with o > 0; exp2 of a large
// negative exponent underflows to 0 (never NaN).
SB_INLINE float oitTransmittance(float a, float o) {
  if (!(o > 0.0f) || !(a > 0.0f)) return 1.0f;
  if (a >= 1.0f) return 0.0f;
  return exp2(max(o * oitLog2OneMinus(a), -200.0f));
}

// The order o of a fragment at depth z among the n fragments of its pixel
// (0 nearest .. n - 1 furthest), paper 3.2: the slab counts before its slab
// plus F_i / B_total * B_before within it, interpolated linearly inside its
// slice (occupancyCount, which needs occupancy_math.glsl included first).
// occupancyCount spreads every fragment over its slice, so the fragment itself
// is part of the count (the furthest gets n): its own share, f for a fragment
// the fraction f into its set slice, is taken out, so one fragment per set
// bit gives the exact orders 0..n-1, and the result is clamped to [0, n - 1].
SB_INLINE float oitOrder(float z, float zMin, float zMax, uint bits[SB_OCC_MAX_WORDS],
                         float slabCounts[SB_OCC_MAX_SLABS], int slices, int slabs) {
  float n = 0.0f;
  for (int i = 0; i < slabs; ++i) n += slabCounts[i];
  if (!(n > 1.0f)) return 0.0f;
  float count = occupancyCount(z, zMin, zMax, bits, slabCounts, slices, slabs, true);
  float self = 0.0f;
  float range = zMax - zMin;
  if (range > 0.0f && z > zMin && z <= zMax) {
    float t = (z - zMin) / range * float(slices);
    int s = min(int(t), slices - 1);
    bool own = (bits[s / 32] & (1u << uint(s % 32))) != 0u;
    self = own ? clamp(t - float(s), 0.0f, 1.0f) : 0.0f;
  }
  return clamp(count - self, 0.0f, n - 1.0f);
}

// order=paper: the order as section 3.2 prints it, the slab counts before
// the fragment's slab plus F_i / B_total * B_before, B_before the set bits of
// the slices in front of the fragment's own slice: every fragment of a slice
// gets the same order, the slice's own fragments are not spread (the default,
// order=corrected, oitOrder above, spreads them and takes out the fragment's
// own share). Clamped to [0, n - 1] as oitOrder is.
SB_INLINE float oitOrderPaper(float z, float zMin, float zMax, uint bits[SB_OCC_MAX_WORDS],
                              float slabCounts[SB_OCC_MAX_SLABS], int slices, int slabs) {
  float n = 0.0f;
  for (int i = 0; i < slabs; ++i) n += slabCounts[i];
  if (!(n > 1.0f)) return 0.0f;
  float range = zMax - zMin;
  if (zMax < zMin || z <= zMin) return 0.0f;
  if (z > zMax || !(range > 0.0f)) return n - 1.0f;
  int s = min(int((z - zMin) / range * float(slices)), slices - 1);
  int perSlab = slices / slabs;
  int slab = s / perSlab;
  int first = slab * perSlab;
  float before = 0.0f;
  for (int i = 0; i < slab; ++i) before += slabCounts[i];
  int setTotal = occupancyBitsBetween(bits, first, first + perSlab);
  float within = setTotal > 0 ? slabCounts[slab] / float(setTotal) *
                                    float(occupancyBitsBetween(bits, first, s))
                              : 0.0f;
  return clamp(before + within, 0.0f, n - 1.0f);
}

// order=printed: section 3.2 as printed in full, the slab counts before the
// fragment's slab plus F_i / B_total * B_before with B_before interpolated
// linearly inside the fragment's own slice (occupancyCount): the fragment's
// own share is not taken out, and nothing clamps it to n - 1 (the furthest
// fragment gets n).
SB_INLINE float oitOrderPrinted(float z, float zMin, float zMax, uint bits[SB_OCC_MAX_WORDS],
                                float slabCounts[SB_OCC_MAX_SLABS], int slices, int slabs) {
  return max(occupancyCount(z, zMin, zMax, bits, slabCounts, slices, slabs, true), 0.0f);
}

// The weight of a fragment of alpha a and order o: (1 - a)^o * a.
SB_INLINE float oitWeight(float a, float o) {
  return oitTransmittance(a, o) * clamp(a, 0.0f, 1.0f);
}

// Lambda = 1 - 2^log2T (1 - (1 - a)^n for one alpha), in [0, 1]; for small
// |x| = |log2T ln 2| the series of -expm1(x) avoids the cancellation of 1 - e^x
// (few fragments of tiny alpha).
SB_INLINE float oitCoverage(float log2T) {
  if (!(log2T < 0.0f)) return 0.0f;
  float x = log2T * 0.69314718f;
  if (x > -1e-3f) return -x * (1.0f + x * (0.5f + x * (1.0f / 6.0f)));
  return clamp(1.0f - exp2(max(log2T, -200.0f)), 0.0f, 1.0f);
}

// The resolve: the accumulated hair (rgb: sum of weight * colour, a: sum of
// weights) and the pixel's log2 transmittance give the premultiplied hair
// colour and its coverage Lambda, put over the background b as
//   f = hair.rgb + (1 - Lambda) b.
// With `lambda` the paper's correction rescales hair.rgb so its weights sum to
// Lambda: hair.rgb * Lambda / hair.a (guarded: no weight, no colour). This
// corrects the printed formula, hair.rgb * hair.a / Lambda (section 3.4),
// which inverts it: hair.a is the sum of the estimated weights, Lambda what
// it should be, so scaling by hair.a / Lambda would square the error (weights
// summing to twice Lambda would double again) instead of removing it; with
// exact orders hair.a = Lambda and both agree. Lambda / hair.a makes the
// weights sum to Lambda, the paper's stated aim ("the intensity of the hair
// colour will be correct").
SB_INLINE vec4 oitResolve(vec4 acc, float log2T, bool lambda) {
  float coverage = oitCoverage(log2T);
  vec3 rgb = vec3(max(acc.x, 0.0f), max(acc.y, 0.0f), max(acc.z, 0.0f));
  if (lambda) rgb = acc.w > 1e-30f ? rgb * (coverage / acc.w) : vec3(0.0f);
  return vec4(rgb, coverage);
}

// The resolve with Lambda as printed (section 3.4, order=printed):
// hair.rgb * hair.a / Lambda (guarded: no coverage, no colour); see oitResolve
// for why this inverts the correction it aims at.
SB_INLINE vec4 oitResolvePrinted(vec4 acc, float log2T) {
  float coverage = oitCoverage(log2T);
  vec3 rgb = vec3(max(acc.x, 0.0f), max(acc.y, 0.0f), max(acc.z, 0.0f));
  rgb = coverage > 1e-30f ? rgb * (max(acc.w, 0.0f) / coverage) : vec3(0.0f);
  return vec4(rgb, coverage);
}
