// The layer math of layers.glsl compiled as C++ for tests, and the CPU side of
// deep opacity maps: the layer boundaries.
#pragma once

#include <algorithm>
#include <vector>

#include "render/common/opacity.h"

// Its GLSL as C++ in sb::glsl, reading glsl::layerBoundsCpu and glsl::layerMapsCpu.
#define SB_LAYERED_GLSL "techniques/dom/layers.glsl"
#include "render/common/layered_glsl.h"

namespace sb {

// DOM boundaries d_0..d_K from layer sizes (s times the spacing, or an
// explicit list of multiples of s); kDomExtend stretches them so the last
// layer reaches past the hair's whole depth range.
inline std::vector<float> domBoundaries(int K, int spacing, float s, const std::vector<float>& list,
                                        int beyond, float range) {
  s = std::max(s, 1e-6f);
  std::vector<float> d(std::size_t(K) + 1, 0.0f);
  for (int k = 1; k <= K; ++k) {
    const float size = !list.empty() ? s * list[std::min(list.size(), std::size_t(k)) - 1]
                       : spacing == glsl::kDomPower ? glsl::domPowerLayerSize(k, K, s)
                                                    : glsl::domLayerSize(k, spacing, s);
    d[std::size_t(k)] = d[std::size_t(k) - 1] + std::max(size, 1e-7f);
  }
  if (beyond == glsl::kDomExtend && d.back() <= range) {
    const float scale = (range * 1.0001f + 1e-6f) / d.back();
    for (float& x : d) x *= scale;
  }
  return d;
}

}  // namespace sb
