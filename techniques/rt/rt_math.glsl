// Ray against strand geometry, shared by the lookup (GLSL) and the CPU BVH and
// its tests (rt_math.h, C++ with GLM). Rays are o + t d with |d| = 1.
// Guarded: ray-traced transparency includes it beside rt's lookup.
#ifndef SB_RT_MATH_GLSL
#define SB_RT_MATH_GLSL
#ifndef SB_INLINE
#define SB_INLINE
#endif

// A segment a..b of radius r as the ray sees it: hit when the ray passes within
// r of the segment's axis at an axis point a + s (b - a) with s in [0, 1). That
// is a capsule's cylinder without its caps: consecutive segments of a strand
// meet without overlap (a chain of capsules would count every joint twice),
// and for a ray along the light direction it is the ribbon of width 2r that
// the light map rasterizes. Returns (hit 0/1, t at the closest approach, s,
// squared distance); a segment parallel to the ray (seen end-on) is no hit.
SB_INLINE vec4 rtSegmentHit(vec3 o, vec3 d, vec3 a, vec3 b, float r) {
  vec3 e = b - a;
  vec3 w0 = o - a;
  float B = dot(d, e);
  float C = dot(e, e);
  float D = dot(d, w0);
  float E = dot(e, w0);
  float denom = C - B * B;
  if (!(denom > 1e-7f * C)) return vec4(0.0f);
  float t = (B * E - C * D) / denom;
  float s = (E - B * D) / denom;
  vec3 gap = w0 + t * d - s * e;
  float g2 = dot(gap, gap);
  bool hit = s >= 0.0f && s < 1.0f && g2 < r * r;
  return vec4(hit ? 1.0f : 0.0f, t, s, g2);
}

// Slab test of the ray against the box lo..hi over t in [0, tMax]; invD is
// 1 / d with zero components replaced by a huge value of their sign.
SB_INLINE bool rtBoxHit(vec3 o, vec3 invD, vec3 lo, vec3 hi, float tMax) {
  vec3 t0 = (lo - o) * invD;
  vec3 t1 = (hi - o) * invD;
  vec3 tn = min(t0, t1);
  vec3 tf = max(t0, t1);
  float enter = max(max(tn.x, tn.y), max(tn.z, 0.0f));
  float leave = min(min(tf.x, tf.y), min(tf.z, tMax));
  return enter <= leave;
}

SB_INLINE vec3 rtSafeInverse(vec3 d) {
  const float kTiny = 1e-20f;
  return vec3(1.0f / (abs(d.x) > kTiny ? d.x : (d.x < 0.0f ? -kTiny : kTiny)),
              1.0f / (abs(d.y) > kTiny ? d.y : (d.y < 0.0f ? -kTiny : kTiny)),
              1.0f / (abs(d.z) > kTiny ? d.z : (d.z < 0.0f ? -kTiny : kTiny)));
}

// The k-th of n ray offsets in a light texel, in [-0.5, 0.5]^2: x stratified,
// y a golden-ratio sequence; one ray is the point itself.
SB_INLINE vec2 rtJitter(int k, int n) {
  float x = (float(k) + 0.5f) / float(n);
  float y = fract(0.5f + float(k) * 0.61803398875f);
  return vec2(x, y) - vec2(0.5f);
}
#endif  // SB_RT_MATH_GLSL
