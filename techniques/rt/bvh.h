// The CPU side of ray-traced shadows: strand segments with a radius, a
// bounding-volume hierarchy over their boxes (median split on the longest axis
// of the centroids), flattened depth first into the node array the lookup
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

// Lays out the subtree of order[first, first + count) depth first (the left
// child right after its parent, so only the right child's index is stored);
// returns its root. Median split: balanced, recursion depth ~log2(n).
inline uint32_t build(Bvh& bvh, const std::vector<glm::vec3>& lo, const std::vector<glm::vec3>& hi,
                      const std::vector<glm::vec3>& mid, uint32_t first, uint32_t count,
                      uint32_t level, uint32_t leafSize) {
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
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  const uint32_t half = count / 2;
  const auto begin = bvh.order.begin() + first;
  std::nth_element(begin, begin + half, begin + count,
                   [&](uint32_t x, uint32_t y) { return mid[x][axis] < mid[y][axis]; });
  build(bvh, lo, hi, mid, first, half, level + 1, leafSize);
  const uint32_t right = build(bvh, lo, hi, mid, first + half, count - half, level + 1, leafSize);
  bvh.nodes[index].leftOrFirst = right;
  bvh.nodes[index].count = 0;
  return index;
}

// Median split: balanced, so the depth is about log2(n / leafSize) + 1 and a
// fixed stack of kMaxStack entries in the shader never overflows.
inline Bvh buildBvh(const std::vector<Segment>& segs, uint32_t leafSize = 4) {
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
  build(bvh, lo, hi, mid, 0, n, 1, std::max(leafSize, 1u));
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
