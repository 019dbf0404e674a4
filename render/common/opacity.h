// The math of opacity.glsl compiled as C++ for tests, and what the opacity-based
// shadows share on the CPU: the hair's depth range from the light (OSM's slicing
// and DOM's layers are in their folders: techniques/osm/slicing.h, techniques/dom/layers.h).
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
#define SB_INLINE inline
#include "render/common/opacity.glsl"
#undef SB_INLINE
}  // namespace glsl

// Window depths from the light of every hair point (the segments' end
// points), clamped to [0,1]. Lines and ribbons are linear in depth between
// their end points, so min/max of these is the hair's exact depth range. The
// points are the device's, or the host's where the device makes them as it
// draws (GpuScene::hostPoints: the mesh path, whose scene.points are the guides).
inline std::vector<float> hairLightDepths(Device& dev, const GpuScene& scene,
                                          const glm::mat4& viewProj) {
  std::vector<float> z;
  if (!scene.hasHair()) return z;
  auto add = [&](const glm::vec3& p) {
    const glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
    if (!(c.w != 0.0f)) return;
    const float d = c.z / c.w;
    if (std::isfinite(d)) z.push_back(std::clamp(d, 0.0f, 1.0f));
  };
  if (scene.hostPoints) {
    z.reserve(scene.hostPoints->size());
    for (const glm::vec3& p : *scene.hostPoints) add(p);
    return z;
  }
  const std::vector<uint8_t> bytes = dev.readBuffer(scene.points);
  const std::size_t n = bytes.size() / sizeof(glm::vec4);
  z.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    glm::vec4 p;
    std::memcpy(&p, bytes.data() + i * sizeof p, sizeof p);
    add(glm::vec3(p));
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

}  // namespace sb
