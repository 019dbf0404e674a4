// The GLSL math of dsm_math.glsl, compiled as C++ for tests, plus a CPU
// driver of the compression over one texel's sorted depths.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace sb::glsl {
using glm::clamp;
using glm::max;
using glm::min;
using glm::vec2;
#define SB_INLINE inline
#define SB_INOUT(T) T&
#include "techniques/dsm/dsm_math.glsl"
#undef SB_INOUT
#undef SB_INLINE
}  // namespace sb::glsl

namespace sb {

// One texel's compressed curve: its nodes (depth, visibility), in order. The
// same steps as techniques/dsm/compress.comp: the first maxNodes nodes are
// kept (truncated = true when there were more).
struct DsmCurve {
  std::vector<glm::vec2> nodes;
  bool truncated = false;
};
inline DsmCurve dsmCompress(const std::vector<float>& sortedDepths, float transmittance, float eps,
                            std::size_t maxNodes = ~std::size_t(0)) {
  DsmCurve c;
  auto keep = [&](const glsl::DsmEmit& e) {
    const glm::vec2 n[3] = {e.n0, e.n1, e.n2};
    for (int i = 0; i < e.count; ++i) {
      if (c.nodes.size() < maxNodes)
        c.nodes.push_back(n[i]);
      else
        c.truncated = true;
    }
  };
  if (sortedDepths.empty()) return c;
  glsl::DsmEmit e{};
  float v = 1.0f;
  std::size_t i = 0;
  // The fragments at one depth drop the visibility together.
  auto next = [&](float& z, float& before, float& after) {
    z = sortedDepths[i];
    before = v;
    while (i < sortedDepths.size() && sortedDepths[i] == z) {
      v *= transmittance;
      ++i;
    }
    after = v;
  };
  float z = 0, before = 0, after = 0;
  next(z, before, after);
  glsl::DsmState s = glsl::dsmStart(z, after, eps, e);
  keep(e);
  while (i < sortedDepths.size()) {
    next(z, before, after);
    glsl::dsmFeed(s, z, before, after, eps, e);
    keep(e);
  }
  glsl::dsmFinish(s, e);
  keep(e);
  return c;
}

// The curve's visibility at depth z (the lookup of techniques/dsm/lookup.glsl).
inline float dsmEvaluate(const std::vector<glm::vec2>& nodes, float z) {
  if (nodes.empty()) return 1.0f;
  std::size_t lo = 0, hi = nodes.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (nodes[mid].x < z)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == 0) return glsl::dsmValue(nodes.front().y);
  if (lo == nodes.size()) return glsl::dsmValue(nodes.back().y);
  return glsl::dsmInterpolate(nodes[lo - 1], nodes[lo], z);
}

}  // namespace sb
