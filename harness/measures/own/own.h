// The own-error measure (harness/measures/own/unit.cpp): each technique's own error. The
// case's transparency technique (oit other than none) against exact transparency with the
// same shadow technique, else its shadow technique against exact shadows with the same
// transparency (README "Ground truth and error"); error.own in the report.
#pragma once

#include <optional>
#include <string>

#include "harness/render.h"

namespace sb {

struct OwnError : MeasureSlice {
  std::string technique;  // "transparency" or "shadow"
  std::string referenceShadow, referenceOit;
  std::optional<ImageError> image;  // with an image
  std::optional<double> flipMean;
  std::optional<VisibilityError> visibility;  // shadow: the same as the total's
  void errorJson(nlohmann::json& error) const override;
};

}  // namespace sb
