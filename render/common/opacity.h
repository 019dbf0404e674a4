// The math of opacity.glsl compiled as C++ for tests, and the CPU side of
// opacity shadow maps and deep opacity maps: the hair's depth range from the
// light, slice placement, layer boundaries.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <vector>

#include "render/common/light_space.h"
#include "render/common/technique.h"

namespace sb {

namespace glsl {
using glm::clamp;
using glm::exp2;
using glm::floor;
using glm::max;
using glm::pow;
// Accessors the shared reconstruction reads through (set by the caller).
inline const float* osmSlicesCpu = nullptr;  // D_0..D_n
inline const float* osmMapsCpu = nullptr;    // map 1..n at [0..n-1]
inline const float* domDCpu = nullptr;       // d_0..d_K
inline const float* domLayersCpu = nullptr;  // layer 1..K at [0..K-1]
#define SB_INLINE inline
#define SB_OSM_SLICE(i) osmSlicesCpu[i]
#define SB_OSM_MAP(i) osmMapsCpu[(i)-1]
#define SB_DOM_D(k) domDCpu[k]
#define SB_DOM_LAYER(k) domLayersCpu[(k)-1]
#include "render/common/opacity.glsl"
#undef SB_DOM_LAYER
#undef SB_DOM_D
#undef SB_OSM_MAP
#undef SB_OSM_SLICE
#undef SB_INLINE
}  // namespace glsl

// Window depths from the light of every hair point (the segments' end
// points), clamped to [0,1]. Lines and ribbons are linear in depth between
// their end points, so min/max of these is the hair's exact depth range.
inline std::vector<float> hairLightDepths(Device& dev, const GpuScene& scene,
                                          const glm::mat4& viewProj) {
  std::vector<float> z;
  if (!scene.hasHair()) return z;
  const std::vector<uint8_t> bytes = dev.readBuffer(scene.points);
  const std::size_t n = bytes.size() / sizeof(glm::vec4);
  z.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    glm::vec4 p;
    std::memcpy(&p, bytes.data() + i * sizeof p, sizeof p);
    const glm::vec4 c = viewProj * glm::vec4(glm::vec3(p), 1.0f);
    if (!(c.w != 0.0f)) continue;
    const float d = c.z / c.w;
    if (std::isfinite(d)) z.push_back(std::clamp(d, 0.0f, 1.0f));
  }
  return z;
}

// hairLightDepths as the opacity techniques slice them: lightDistance
// (light_space.glsl), linear in distance for a point light.
inline std::vector<float> hairLightDistances(Device& dev, const GpuScene& scene,
                                             const glm::mat4& viewProj) {
  std::vector<float> z = hairLightDepths(dev, scene, viewProj);
  for (float& d : z) d = std::clamp(glsl::lightDistance(viewProj, d), 0.0f, 1.0f);
  return z;
}

struct DepthRange {
  float nearZ = 0.0f, farZ = 1.0f;
};
inline DepthRange depthRange(const std::vector<float>& z) {
  if (z.empty()) return {};
  const auto [lo, hi] = std::minmax_element(z.begin(), z.end());
  return {*lo, *hi};
}

// The hair's depth range from the light (hairLightDepths), widened by 1e-3 of
// its extent on both sides so that no fragment sits on its ends.
inline DepthRange paddedHairDepthRange(Device& dev, const GpuScene& scene,
                                       const glm::mat4& viewProj) {
  const DepthRange r = depthRange(hairLightDepths(dev, scene, viewProj));
  const float pad = 1e-3f * std::max(r.farZ - r.nearZ, 1e-6f);
  return {r.nearZ - pad, r.farZ + pad};
}

// OSM slice depths D_0..D_n. D_n is nudged past the farthest hair so that
// the last map counts every fragment. Density slicing (the paper's 1D BSP):
// equal numbers of hair points per slice, from the sorted point depths.
inline std::vector<float> osmSlices(int n, int mode, float gamma, std::vector<float> z) {
  const DepthRange r = depthRange(z);
  std::vector<float> d(std::size_t(n) + 1);
  for (int i = 0; i <= n; ++i)
    d[std::size_t(i)] = glsl::osmSliceDepth(i, n, r.nearZ, r.farZ, mode, gamma);
  if (mode == glsl::kOsmDensity && !z.empty()) {
    std::sort(z.begin(), z.end());
    for (int i = 1; i < n; ++i)
      d[std::size_t(i)] = z[std::min(z.size() - 1, std::size_t(double(i) / n * double(z.size())))];
  }
  d[std::size_t(n)] = std::nextafter(r.farZ + 1e-6f, 2.0f);
  for (std::size_t i = 1; i < d.size(); ++i) d[i] = std::max(d[i], d[i - 1]);
  return d;
}

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
