// The slicing math of slicing.glsl compiled as C++ for tests, and the CPU side
// of opacity shadow maps: slice placement from the hair's depths.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/common/opacity.h"

// Its GLSL as C++ in sb::glsl, reading glsl::layerBoundsCpu and glsl::layerMapsCpu.
#define SB_LAYERED_GLSL "techniques/osm/slicing.glsl"
#include "render/common/layered_glsl.h"

namespace sb {

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

}  // namespace sb
