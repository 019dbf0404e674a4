// The animation measure (harness/measures/animation/unit.cpp; render --animate): every frame
// of a light or camera orbit rendered by the technique and by the reference, each frame's
// error and the flicker.
#pragma once

#include <optional>
#include <vector>

#include "harness/render.h"

namespace sb {

// One animation frame's error against that frame's reference.
struct AnimationFrame {
  int frame = 0;
  double degrees = 0;
  std::optional<double> imageRmse, flipMean;  // with an image
  double visibilityRmse = 0;
};

// The error of an animation. Flicker: the mean over frames t >= 1 and pixels of
// |(T_t - T_{t-1}) - (R_t - R_{t-1})|, the technique's frame-to-frame change that the
// reference does not have (image: RGB channels; visibility: pixels where all four frames
// see a surface).
struct AnimationResult : MeasureSlice {
  AnimateSpec spec;
  std::vector<AnimationFrame> frames;
  std::optional<double> imageFlicker;  // with an image
  double visibilityFlicker = 0;
  std::size_t visibilityPixels = 0;  // pixel pairs the visibility flicker averages
  // A few frames for a strip in reports: their indices, the technique's and the
  // reference's images (with an image).
  std::vector<int> stripFrames;
  std::vector<Image> stripImages, stripReferences;
  void json(nlohmann::json& report) const override;
};

// An animation's strip: its strip frames side by side, the technique's above
// the reference's, 2-pixel white gaps (empty without an image).
Image animationStrip(const AnimationResult& a);

}  // namespace sb
