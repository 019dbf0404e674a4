// Adaptive volumetric shadow maps (Salvi, Vidimce, Lauritzen & Lefohn, EGSR
// 2010): a light texel's transmittance as a piecewise-linear curve of at most
// `budget` nodes (depth, transmittance), kept sorted front to back, built by
// streaming insertion of each occluder with lossy compression. Pure math,
// compiled as GLSL and, through avsm_math.h, as C++ with GLM for CPU tests.
//
// Insertion. The paper inserts an occluder as a light-aligned segment (entry,
// exit, transmittance at the exit): the curve keeps its value up to the entry
// and every node behind is multiplied by the segment's transmittance. A hair
// fragment is a segment of no thickness (the paper's "well-localized denser
// media such as hair"), so it inserts two nodes at its depth d: (d, T(d)) and
// (d, T(d) (1 - alpha)), a vertical step, and scales the nodes behind d.
// T(d) is the curve's value behind every node at or in front of d, so
// fragments at one depth drop the curve together, as the exact visibility.
//
// Compression. When the curve has more than `budget` nodes, the node whose
// removal changes the area under the curve least is removed, one at a time
// until it fits; removing node i replaces the segments i-1..i..i+1 by one,
// which changes the area by exactly the triangle (i-1, i, i+1). The first and
// the last node are never removed (the paper: the last carries the shadow
// behind the whole volume); nodes are not moved after a removal. Ties go to
// the frontmost node, so GL, Vulkan and the CPU agree.
//
// Every node's transmittance is a product of factors in [0, 1] and the nodes
// fall front to back (insertion keeps the order and removal keeps a subset),
// so the curve is in [0, 1] and never rises away from the light. The first
// node always has transmittance 1 (nothing lies in front of the frontmost
// fragment), so in front of the curve the visibility is 1.
//
// SB_AVSM_CAP: the array size, at least budget + 2 (the two nodes an
// insertion adds before the compression runs).
#ifndef SB_INLINE
#define SB_INLINE
#endif
#ifndef SB_INOUT
#define SB_INOUT(T) inout T
#endif

struct AvsmCurve {
  vec2 n[SB_AVSM_CAP];  // (depth, transmittance), front to back
  int count;
};

SB_INLINE AvsmCurve avsmEmpty() {
  AvsmCurve c;
  for (int i = 0; i < SB_AVSM_CAP; ++i) c.n[i] = vec2(0.0f, 1.0f);
  c.count = 0;
  return c;
}

// Linear interpolation between two nodes at depth z (a.x <= z <= b.x).
SB_INLINE float avsmLerp(vec2 a, vec2 b, float z) {
  float w = clamp((z - a.x) / max(b.x - a.x, 1e-30f), 0.0f, 1.0f);
  return clamp(a.y + (b.y - a.y) * w, 0.0f, 1.0f);
}

// The curve at depth z: `behind` false looks up a receiver at z (nodes at z
// count as behind it: a fragment at exactly the receiver's depth does not
// shadow it, as in the exact visibility); true gives the value behind every
// node at or in front of z (the value an insertion at z starts from).
SB_INLINE float avsmValue(AvsmCurve c, float z, bool behind) {
  if (c.count == 0) return 1.0f;
  int i = 0;  // the first node deeper than z (behind) or at or deeper than z
  while (i < c.count && (behind ? c.n[i].x <= z : c.n[i].x < z)) ++i;
  if (i == 0) return clamp(c.n[0].y, 0.0f, 1.0f);
  if (i == c.count) return clamp(c.n[c.count - 1].y, 0.0f, 1.0f);
  return avsmLerp(c.n[i - 1], c.n[i], z);
}

// The change of the area under the curve when interior node i is removed:
// the triangle of nodes i-1, i, i+1.
SB_INLINE float avsmRemovalArea(AvsmCurve c, int i) {
  vec2 a = c.n[i - 1], b = c.n[i], d = c.n[i + 1];
  return 0.5f * abs((b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y));
}

// Removes the interior node of least removal area (the frontmost of equals).
SB_INLINE int avsmRemoveOne(SB_INOUT(AvsmCurve) c) {
  int best = 1;
  float bestArea = avsmRemovalArea(c, 1);
  for (int i = 2; i < c.count - 1; ++i) {
    float a = avsmRemovalArea(c, i);
    if (a < bestArea) {
      bestArea = a;
      best = i;
    }
  }
  for (int i = best; i < c.count - 1; ++i) c.n[i] = c.n[i + 1];
  c.count -= 1;
  return best;
}

// Streams one fragment at depth d of transmittance t = 1 - alpha into the
// curve, then compresses it to `budget` nodes (budget >= 3, <= SB_AVSM_CAP - 2).
// Returns the nodes removed.
SB_INLINE int avsmInsert(SB_INOUT(AvsmCurve) c, float d, float t, int budget) {
  t = clamp(t, 0.0f, 1.0f);
  float v = avsmValue(c, d, true);
  int at = 0;
  while (at < c.count && c.n[at].x <= d) ++at;
  for (int i = c.count - 1; i >= at; --i) c.n[i + 2] = vec2(c.n[i].x, c.n[i].y * t);
  c.n[at] = vec2(d, v);
  c.n[at + 1] = vec2(d, v * t);
  c.count += 2;
  int removed = 0;
  while (c.count > budget) {
    avsmRemoveOne(c);
    removed += 1;
  }
  return removed;
}
