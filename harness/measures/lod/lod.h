// The level-of-detail measure (harness/measures/lod/unit.cpp; scene lod= or lod_pixels=,
// docs/geometry.md): what each instance kept, and the image's error against the full
// model's exact reference (with a reference and an image; error.image is against the
// strands drawn).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/render.h"

namespace sb {

struct LevelOfDetail : MeasureSlice {
  std::string by;  // "lod" (a fixed share) or "lod_pixels" (by size on screen)
  double setting = 0;
  std::size_t strandsFull = 0, strandsDrawn = 0;
  std::vector<double> shares;  // per instance: kept / strands
  std::optional<ImageError> fullModelError;
  void json(nlohmann::json& report) const override;      // lod
  void errorJson(nlohmann::json& error) const override;  // error.full_model
};

}  // namespace sb
