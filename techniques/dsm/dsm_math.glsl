// Deep shadow maps (Lokovic & Veach 2000): a light texel's visibility
// function, compressed to a piecewise-linear curve that stays within epsilon
// of it everywhere. Pure math, compiled as GLSL and, through dsm_math.h, as
// C++ with GLM for CPU tests.
//
// The input is the exact visibility of one texel: a step function that starts
// at 1 and drops at each distinct fragment depth u_k from vBefore_k to vAfter_k
// (= (1 - alpha)^(fragments up to u_k)); a point exactly at u_k sees vBefore_k
// (the exact lookup counts the fragments strictly in front).
//
// The compression is the paper's greedy algorithm (section 4.2, "Compression"):
// from the current anchor, keep the cone of slopes [lo, hi] of the lines that
// stay within epsilon of every constraint seen so far; extend the segment
// while the cone is not empty, then end it with the middle slope and start the
// next one from its end. A constant piece between two depths is checked at
// its two ends (a line's error on it is largest there), so each depth u_k is a
// constraint on the left limit (vBefore_k) and the right limit (vAfter_k). A
// drop larger than 2 epsilon cannot be crossed by a line: there the curve gets
// a vertical step, two nodes at the same depth (the paper's discontinuities),
// the first within epsilon of vBefore_k, the second within epsilon of
// vAfter_k. With epsilon 0 every drop is such a step and the curve is the
// exact function.
//
// Slopes are kept <= 0, so the curve never rises away from the light, as
// the visibility it stands for (always possible: each anchor is within
// epsilon of the visibility there, which only falls).
//
// The lookup (dsmInterpolate) finds the first node at or behind the depth z
// (lower bound) and interpolates from the node before it; in front of the
// first node the visibility is the first node's, behind the last the last's.
#ifndef SB_INLINE
#define SB_INLINE
#endif
#ifndef SB_INOUT
#define SB_INOUT(T) inout T
#endif

#define SB_DSM_BIG 1e30f

struct DsmState {
  float az, av;  // the anchor: where the open segment starts
  float lo, hi;  // its cone of slopes (valid when open)
  float pz;      // the last depth inside the open segment
  bool open;     // a segment with constraints is in progress
};

// Up to 3 nodes made by one step (written by the caller, in order).
struct DsmEmit {
  vec2 n0, n1, n2;
  int count;
};

SB_INLINE void dsmPush(SB_INOUT(DsmEmit) e, float z, float v) {
  if (e.count == 0) e.n0 = vec2(z, v);
  else if (e.count == 1) e.n1 = vec2(z, v);
  else e.n2 = vec2(z, v);
  e.count += 1;
}

// The first depth u_0: the curve starts at visibility 1, and steps down to
// within epsilon of vAfter there when 1 is not.
SB_INLINE DsmState dsmStart(float z, float vAfter, float eps, SB_INOUT(DsmEmit) e) {
  DsmState s;
  s.az = z;
  s.av = 1.0f;
  s.lo = -SB_DSM_BIG;
  s.hi = 0.0f;
  s.pz = z;
  s.open = false;
  e.count = 0;
  dsmPush(e, z, 1.0f);
  float v = clamp(1.0f, vAfter - eps, vAfter + eps);
  if (v != 1.0f) {
    dsmPush(e, z, v);
    s.av = v;
  }
  return s;
}

// The next depth u_k (greater than every earlier one).
SB_INLINE void dsmFeed(SB_INOUT(DsmState) s, float z, float vBefore, float vAfter, float eps,
                       SB_INOUT(DsmEmit) e) {
  e.count = 0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    float dz = z - s.az;
    float lo = s.open ? s.lo : -SB_DSM_BIG;
    float hi = s.open ? s.hi : 0.0f;  // never rising: the curve is non-increasing
    // Both limits at u_k: the line may continue through it.
    if (vBefore - vAfter <= 2.0f * eps) {
      float l = max(lo, (vBefore - eps - s.av) / dz);
      float h = min(hi, (vAfter + eps - s.av) / dz);
      if (l <= h) {
        s.lo = l;
        s.hi = h;
        s.pz = z;
        s.open = true;
        return;
      }
    }
    // The left limit only: the segment ends at u_k, the curve steps down there.
    float l = max(lo, (vBefore - eps - s.av) / dz);
    float h = min(hi, (vBefore + eps - s.av) / dz);
    if (l <= h) {
      float ev = clamp(s.av + 0.5f * (l + h) * dz, vBefore - eps, vBefore + eps);
      dsmPush(e, z, ev);
      float nv = clamp(ev, vAfter - eps, vAfter + eps);
      if (nv != ev) dsmPush(e, z, nv);
      s.az = z;
      s.av = nv;
      s.open = false;
      return;
    }
    // Neither: end the open segment at the last depth it reached, and retry
    // from there (a fresh cone always takes the left limit).
    float ev = s.av + 0.5f * (s.lo + s.hi) * (s.pz - s.az);
    dsmPush(e, s.pz, ev);
    s.az = s.pz;
    s.av = ev;
    s.open = false;
  }
}

// After the last depth: ends the open segment, if any, at it.
SB_INLINE void dsmFinish(SB_INOUT(DsmState) s, SB_INOUT(DsmEmit) e) {
  e.count = 0;
  if (!s.open) return;
  dsmPush(e, s.pz, s.av + 0.5f * (s.lo + s.hi) * (s.pz - s.az));
  s.open = false;
}

// A node value as visibility: within epsilon of a function in [0, 1] the
// curve may stray below 0 (or, in principle, above 1); clamping it there only
// brings it closer to the function, so the bound and the fall still hold.
SB_INLINE float dsmValue(float v) { return clamp(v, 0.0f, 1.0f); }

// The curve at depth z, given the lower bound: `after` is the first node at
// or behind z, `before` the node in front of it (before.x < z <= after.x).
SB_INLINE float dsmInterpolate(vec2 before, vec2 after, float z) {
  float w = clamp((z - before.x) / max(after.x - before.x, 1e-30f), 0.0f, 1.0f);
  return dsmValue(before.y + (after.y - before.y) * w);
}
