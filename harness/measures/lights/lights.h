// The lights measure (harness/measures/lights/unit.cpp): with extra lights, each light's
// share of the timed frames and of the memory, the key light first.
#pragma once

#include <vector>

#include "harness/render.h"

namespace sb {

// One light's share, told apart by the names of passes and resources
// (Renderer::lightPrefix); "lights.sum" belongs to none.
struct LightShare {
  Light light;
  std::vector<double> ms;       // per timed frame: the sum of its passes
  std::size_t shadowBytes = 0;  // its shadow technique's resources
  std::size_t bytes = 0;  // all its own (the key light's: all but the scene's and the others')
};

struct LightShares : MeasureSlice {
  std::vector<LightShare> lights;  // the key light first
  void json(nlohmann::json& report) const override;
};

}  // namespace sb
