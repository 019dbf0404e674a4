// The probe measure (harness/measures/probe/unit.cpp; render --probe): visibility along one
// light ray, the exact curve and the technique's (the occupancy paper's Fig. 5).
#pragma once

#include <vector>

#include "harness/render.h"

namespace sb {

struct ProbeResult : MeasureSlice {
  glm::uvec2 texel{0, 0};
  uint32_t mapSize = 0;
  std::vector<float> lightDepth, exact, visibility;
  void json(nlohmann::json& report) const override;
};

}  // namespace sb
