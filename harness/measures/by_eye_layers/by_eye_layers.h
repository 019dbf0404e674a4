// The error by eye layers (harness/measures/by_eye_layers/unit.cpp): the error over the
// pixels whose eye depth complexity (hair fragments in the reference) is in buckets 0, 1,
// 2-3, 4-7, ...: where a technique breaks. error.by_eye_layers in the report.
#pragma once

#include <optional>
#include <vector>

#include "harness/render.h"

namespace sb {

struct LayerBucket {
  uint32_t lo = 0, hi = 0;
  std::size_t pixels = 0;
  std::optional<double> imageMeanAbs, flipMean;  // with an image; mean |T - R| over RGB
  std::optional<double> visibilityMeanAbs;       // over the pixels with a surface in both
};

struct ErrorByEyeLayers : MeasureSlice {
  std::vector<LayerBucket> buckets;
  void errorJson(nlohmann::json& error) const override;
};

}  // namespace sb
