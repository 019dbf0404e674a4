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
// The curve is reached through two macros the includer defines:
// SB_AVSM_N(i), node i (a vec2 lvalue: depth, transmittance), and
// SB_AVSM_COUNT, the node count (an int lvalue), with room for budget + 2
// nodes (the two an insertion adds before the compression runs). The resolve
// keeps the curve in the storage buffer itself: in a local array (a struct
// passed inout, or a global), Mesa's GL compiled the dynamically indexed
// removal wrong (GL's curves stopped changing at the first removal; Vulkan's
// and the CPU's were right).
#ifndef SB_INLINE
#define SB_INLINE
#endif
// The removal compares areas that are often nearly equal: computed without
// fused multiply-adds (GLSL `precise`; plain arithmetic in the C++), so GL,
// Vulkan and the CPU round them alike and remove the same node.
#ifndef SB_PRECISE
#define SB_PRECISE precise
#endif

// Linear interpolation between two nodes at depth z (a.x <= z <= b.x).
SB_INLINE float avsmLerp(vec2 a, vec2 b, float z) {
  SB_PRECISE float w = clamp((z - a.x) / max(b.x - a.x, 1e-30f), 0.0f, 1.0f);
  SB_PRECISE float v = a.y + (b.y - a.y) * w;
  return clamp(v, 0.0f, 1.0f);
}

// The curve at depth z: `behind` false looks up a receiver at z (nodes at z
// count as behind it: a fragment at exactly the receiver's depth does not
// shadow it, as in the exact visibility); true gives the value behind every
// node at or in front of z (the value an insertion at z starts from).
SB_INLINE float avsmValue(float z, bool behind) {
  int count = SB_AVSM_COUNT;
  if (count == 0) return 1.0f;
  int i = 0;  // the first node deeper than z (behind) or at or deeper than z
  while (i < count && (behind ? SB_AVSM_N(i).x <= z : SB_AVSM_N(i).x < z)) ++i;
  if (i == 0) return clamp(SB_AVSM_N(0).y, 0.0f, 1.0f);
  if (i == count) return clamp(SB_AVSM_N(count - 1).y, 0.0f, 1.0f);
  return avsmLerp(SB_AVSM_N(i - 1), SB_AVSM_N(i), z);
}

#ifndef SB_AVSM_READ_ONLY
// The change of the area under the curve when interior node i is removed:
// the triangle of nodes i-1, i, i+1.
SB_INLINE float avsmRemovalArea(int i) {
  float ax = SB_AVSM_N(i - 1).x, ay = SB_AVSM_N(i - 1).y;
  float bx = SB_AVSM_N(i).x, by = SB_AVSM_N(i).y;
  float dx = SB_AVSM_N(i + 1).x, dy = SB_AVSM_N(i + 1).y;
  SB_PRECISE float p = (bx - ax) * (dy - ay);
  SB_PRECISE float q = (dx - ax) * (by - ay);
  SB_PRECISE float twice = p - q;
  return 0.5f * (twice < 0.0f ? -twice : twice);
}

// Removes the interior node of least removal area (the frontmost of equals);
// returns its index.
SB_INLINE int avsmRemoveOne() {
  int count = SB_AVSM_COUNT;
  int best = 1;
  float bestArea = avsmRemovalArea(1);
  for (int i = 2; i + 1 < count; ++i) {
    float a = avsmRemovalArea(i);
    if (a < bestArea) {
      bestArea = a;
      best = i;
    }
  }
  for (int i = best; i < count - 1; ++i) SB_AVSM_N(i) = SB_AVSM_N(i + 1);
  SB_AVSM_COUNT = count - 1;
  return best;
}

// Streams one fragment at depth d of transmittance t = 1 - alpha into the
// curve (two nodes more). Then removes nodes until it has at most `budget`
// (3 <= budget, and room for budget + 2); returns the nodes removed.
SB_INLINE int avsmInsert(float d, float t, int budget) {
  t = clamp(t, 0.0f, 1.0f);
  float v = avsmValue(d, true);
  int count = SB_AVSM_COUNT;
  int at = 0;
  while (at < count && SB_AVSM_N(at).x <= d) ++at;
  for (int i = count - 1; i >= at; --i) {
    SB_PRECISE float behind = SB_AVSM_N(i).y * t;
    SB_AVSM_N(i + 2) = vec2(SB_AVSM_N(i).x, behind);
  }
  SB_PRECISE float after = v * t;
  SB_AVSM_N(at) = vec2(d, v);
  SB_AVSM_N(at + 1) = vec2(d, after);
  SB_AVSM_COUNT = count + 2;
  int removed = 0;
  while (SB_AVSM_COUNT > budget) {
    avsmRemoveOne();
    removed += 1;
  }
  return removed;
}
#endif
