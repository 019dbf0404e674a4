// One pixel's (or light texel's) occupancy maps built on the CPU from fragment depths, as the
// occupancy and slab passes build them, with the two lookups of occupancy_oit_math.h over
// them: for the tests of the order (transparency) and the count (shadows).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "techniques/occupancy_oit/occupancy_oit_math.h"

namespace sbtest {

struct OccupancyMaps {
  uint32_t bits[SB_OCC_MAX_WORDS] = {};
  float slabs[SB_OCC_MAX_SLABS] = {};
  float zMin = 2.0f, zMax = -2.0f;
  int slices, slabCount;
  OccupancyMaps(const std::vector<float>& z, int nSlices, int nSlabs)
      : slices(nSlices), slabCount(nSlabs) {
    for (float d : z) zMin = std::min(zMin, d), zMax = std::max(zMax, d);
    for (float d : z) {
      const int s = sb::glsl::occupancySlice(d, zMin, zMax, slices);
      bits[s / 32] |= 1u << (s % 32);
      slabs[s / (slices / slabCount)] += 1.0f;
    }
  }
  float order(float z) {
    return sb::glsl::oitOrder(z, zMin, zMax, bits, slabs, slices, slabCount);
  }
  float count(float z, bool useSlabs) {
    return sb::glsl::occupancyCount(z, zMin, zMax, bits, slabs, slices, slabCount, useSlabs);
  }
};

}  // namespace sbtest
