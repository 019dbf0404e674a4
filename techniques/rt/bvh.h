// The CPU side of ray-traced shadows: strand segments with a radius, a
// bounding-volume hierarchy over their boxes (binned SAH, or median split on
// the longest axis of the centroids), flattened depth first into the node array the lookup
// walks (techniques/rt/lookup.glsl), and a CPU traversal for tests. No GPU.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <limits>
#include <numeric>
#include <vector>

#include "techniques/rt/rt_math.h"

namespace sb::rt {

struct Segment {
  glm::vec3 a, b;
  float radius = 0;
};

// 32 bytes, two vec4 in the shader: (lo, leftOrFirst bits), (hi, count bits).
// Interior nodes (count 0): the left child is the next node, the right child
// is at leftOrFirst. Leaves: segments [leftOrFirst, leftOrFirst + count) of
// the reordered segment array.
struct Node {
  glm::vec3 lo;
  uint32_t leftOrFirst = 0;
  glm::vec3 hi;
  uint32_t count = 0;
};
static_assert(sizeof(Node) == 32, "two vec4 in the shader");

struct Bvh {
  std::vector<Node> nodes;
  std::vector<uint32_t> order;  // segment index of each slot of the reordered array
  uint32_t depth = 0;           // levels, the root's included: the shader's stack needs depth
};

inline void segmentBounds(const Segment& s, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::min(s.a, s.b) - glm::vec3(s.radius);
  hi = glm::max(s.a, s.b) + glm::vec3(s.radius);
}

// Binned surface area heuristic: 16 bins of the centroids per axis, the split
// of least area(left) n(left) + area(right) n(right). Partitions
// order[first, first + count) and returns the left count (0: no split found).
// Only the first kSahLevels levels use it; median splits below keep the depth
// within the shader's stack (kSahLevels + log2(n)).
constexpr uint32_t kSahLevels = 24;
inline float halfArea(glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 e = glm::max(hi - lo, glm::vec3(0.0f));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}
inline uint32_t sahSplit(Bvh& bvh, const std::vector<glm::vec3>& lo,
                         const std::vector<glm::vec3>& hi, const std::vector<glm::vec3>& mid,
                         uint32_t first, uint32_t count, glm::vec3 clo, glm::vec3 ext) {
  constexpr int kBins = 16;
  const float big = std::numeric_limits<float>::max();
  float bestCost = big;
  int bestAxis = -1, bestBin = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(ext[axis] > 0.0f)) continue;
    glm::vec3 blo[kBins], bhi[kBins];
    uint32_t n[kBins] = {};
    for (int b = 0; b < kBins; ++b) blo[b] = glm::vec3(big), bhi[b] = glm::vec3(-big);
    const float scale = float(kBins) / ext[axis];
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t s = bvh.order[i];
      const int b = std::min(kBins - 1, int((mid[s][axis] - clo[axis]) * scale));
      ++n[b];
      blo[b] = glm::min(blo[b], lo[s]);
      bhi[b] = glm::max(bhi[b], hi[s]);
    }
    // Right-hand sums, then a sweep from the left.
    float rightArea[kBins];
    uint32_t rightCount[kBins];
    glm::vec3 rlo(big), rhi(-big);
    uint32_t rn = 0;
    for (int b = kBins - 1; b > 0; --b) {
      rlo = glm::min(rlo, blo[b]);
      rhi = glm::max(rhi, bhi[b]);
      rn += n[b];
      rightArea[b] = halfArea(rlo, rhi);
      rightCount[b] = rn;
    }
    glm::vec3 llo(big), lhi(-big);
    uint32_t ln = 0;
    for (int b = 1; b < kBins; ++b) {  // split before bin b
      llo = glm::min(llo, blo[b - 1]);
      lhi = glm::max(lhi, bhi[b - 1]);
      ln += n[b - 1];
      if (ln == 0 || rightCount[b] == 0) continue;
      const float cost = halfArea(llo, lhi) * float(ln) + rightArea[b] * float(rightCount[b]);
      if (cost < bestCost) bestCost = cost, bestAxis = axis, bestBin = b;
    }
  }
  if (bestAxis < 0) return 0;
  const float scale = float(kBins) / ext[bestAxis];
  const auto it =
      std::partition(bvh.order.begin() + first, bvh.order.begin() + first + count, [&](uint32_t s) {
        return std::min(kBins - 1, int((mid[s][bestAxis] - clo[bestAxis]) * scale)) < bestBin;
      });
  return uint32_t(it - (bvh.order.begin() + first));
}

// Lays out the subtree of order[first, first + count) depth first (the left
// child right after its parent, so only the right child's index is stored);
// returns its root. Split by SAH (sah) or at the median of the longest axis.
inline uint32_t build(Bvh& bvh, const std::vector<glm::vec3>& lo, const std::vector<glm::vec3>& hi,
                      const std::vector<glm::vec3>& mid, uint32_t first, uint32_t count,
                      uint32_t level, uint32_t leafSize, bool sah) {
  bvh.depth = std::max(bvh.depth, level);
  glm::vec3 blo(std::numeric_limits<float>::max()), bhi(-std::numeric_limits<float>::max());
  glm::vec3 clo = blo, chi = bhi;
  for (uint32_t i = first; i < first + count; ++i) {
    const uint32_t s = bvh.order[i];
    blo = glm::min(blo, lo[s]);
    bhi = glm::max(bhi, hi[s]);
    clo = glm::min(clo, mid[s]);
    chi = glm::max(chi, mid[s]);
  }
  const uint32_t index = uint32_t(bvh.nodes.size());
  bvh.nodes.push_back({blo, first, bhi, count});
  if (count <= leafSize) return index;
  const glm::vec3 ext = chi - clo;
  const auto begin = bvh.order.begin() + first;
  uint32_t half =
      sah && level < kSahLevels ? sahSplit(bvh, lo, hi, mid, first, count, clo, ext) : 0;
  if (half == 0 || half >= count) {  // median split on the longest axis
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    half = count / 2;
    std::nth_element(begin, begin + half, begin + count,
                     [&](uint32_t x, uint32_t y) { return mid[x][axis] < mid[y][axis]; });
  }
  build(bvh, lo, hi, mid, first, half, level + 1, leafSize, sah);
  const uint32_t right =
      build(bvh, lo, hi, mid, first + half, count - half, level + 1, leafSize, sah);
  bvh.nodes[index].leftOrFirst = right;
  bvh.nodes[index].count = 0;
  return index;
}

// Leaves of at most leafSize segments. Median splits are balanced: depth about
// log2(n / leafSize) + 1; SAH splits (the default) are not, and fall back to
// the median below kSahLevels, so the shader's stack of 48 suffices.
inline Bvh buildBvh(const std::vector<Segment>& segs, uint32_t leafSize = 4, bool sah = true) {
  Bvh bvh;
  const uint32_t n = uint32_t(segs.size());
  bvh.order.resize(n);
  std::iota(bvh.order.begin(), bvh.order.end(), 0u);
  if (n == 0) {  // one leaf of packSegments' zero-length segment, which no ray hits
    bvh.nodes.push_back({glm::vec3(0.0f), 0, glm::vec3(0.0f), 1});
    bvh.depth = 1;
    return bvh;
  }
  std::vector<glm::vec3> lo(n), hi(n), mid(n);
  for (uint32_t i = 0; i < n; ++i) {
    segmentBounds(segs[i], lo[i], hi[i]);
    mid[i] = 0.5f * (lo[i] + hi[i]);
  }
  bvh.nodes.reserve(2 * (n / std::max(leafSize, 1u) + 1));
  build(bvh, lo, hi, mid, 0, n, 1, std::max(leafSize, 1u), sah);
  return bvh;
}

// The shader's walk, on the CPU: the number of segments hit by the ray o + t d
// (|d| = 1) with t in (tMin, tMax), each counted once.
inline uint32_t countHits(const Bvh& bvh, const std::vector<Segment>& segs, glm::vec3 o,
                          glm::vec3 d, float tMin, float tMax) {
  const glm::vec3 inv = glsl::rtSafeInverse(d);
  uint32_t hits = 0;
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const Node& n = bvh.nodes[stack.back()];
    const uint32_t index = uint32_t(&n - bvh.nodes.data());
    stack.pop_back();
    if (!glsl::rtBoxHit(o, inv, n.lo, n.hi, tMax)) continue;
    if (n.count == 0) {
      stack.push_back(n.leftOrFirst);
      stack.push_back(index + 1);
      continue;
    }
    const uint32_t end = std::min<uint32_t>(n.leftOrFirst + n.count, uint32_t(bvh.order.size()));
    for (uint32_t i = n.leftOrFirst; i < end; ++i) {
      const Segment& s = segs[bvh.order[i]];
      const glm::vec4 h = glsl::rtSegmentHit(o, d, s.a, s.b, s.radius);
      if (h.x > 0.0f && h.y > tMin && h.y < tMax) ++hits;
    }
  }
  return hits;
}

// The bytes the shader reads: nodes as they are, segments in BVH order as two
// vec4 each, (a, radius) and (b, 0).
inline std::vector<glm::vec4> packSegments(const Bvh& bvh, const std::vector<Segment>& segs) {
  std::vector<glm::vec4> out;
  out.reserve(std::max<std::size_t>(2 * bvh.order.size(), 2));
  for (uint32_t i : bvh.order) {
    out.emplace_back(segs[i].a, segs[i].radius);
    out.emplace_back(segs[i].b, 0.0f);
  }
  if (out.empty()) out.assign(2, glm::vec4(0.0f));  // a buffer may not be empty
  return out;
}

}  // namespace sb::rt
