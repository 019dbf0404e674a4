// The error by eye layers (by_eye_layers.h).
#include <bit>
#include <cmath>

#include "harness/measures/by_eye_layers/by_eye_layers.h"
#include "harness/measures/measure_unit.h"

namespace sb {
namespace {

std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  if (!in.req.reference || !in.reference || !in.reference->eye) return nullptr;
  const RenderResult& out = in.out;
  const DepthComplexity& eye = *in.reference->eye;
  const std::size_t w = out.width, h = out.height;
  if (eye.counts.size() != w * h) return nullptr;
  auto bucketOf = [](uint32_t n) { return n == 0 ? 0 : 1 + int(std::bit_width(n)) - 1; };
  const std::vector<float> vt = visibilityFloats(out.visibility);
  const std::vector<float> vr = visibilityFloats(in.reference->visibility);
  struct Sum {
    std::size_t pixels = 0, visPixels = 0;
    double image = 0, flip = 0, vis = 0;
  };
  std::vector<Sum> sums;
  const bool image = !out.image.pixels.empty() && out.flip;
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t gpu = y * w + x;  // bottom-up, as counts and visibility
      const std::size_t top = (h - 1 - y) * w + x;
      const std::size_t b = bucketOf(eye.counts[gpu]);
      if (sums.size() <= b) sums.resize(b + 1);
      Sum& s = sums[b];
      ++s.pixels;
      if (image) {
        const int c = out.image.channels;
        for (int k = 0; k < 3; ++k)
          s.image += std::fabs(double(out.image.pixels[top * c + k]) -
                               double(out.referenceImage.pixels[top * c + k])) /
                     3.0;
        s.flip += out.flip->map[top];
      }
      if (gpu < vt.size() && gpu < vr.size() && vt[gpu] >= 0 && vr[gpu] >= 0) {
        ++s.visPixels;
        s.vis += std::fabs(double(vt[gpu]) - double(vr[gpu]));
      }
    }
  auto result = std::make_shared<ErrorByEyeLayers>();
  for (std::size_t b = 0; b < sums.size(); ++b) {
    const Sum& s = sums[b];
    if (s.pixels == 0) continue;
    LayerBucket k;
    k.lo = b == 0 ? 0 : 1u << (b - 1);
    k.hi = b == 0 ? 0 : (1u << (b - 1)) * 2 - 1;
    k.pixels = s.pixels;
    if (image) {
      k.imageMeanAbs = s.image / double(s.pixels);
      k.flipMean = s.flip / double(s.pixels);
    }
    if (s.visPixels) k.visibilityMeanAbs = s.vis / double(s.visPixels);
    result->buckets.push_back(k);
  }
  if (result->buckets.empty()) return nullptr;
  return result;
}

}  // namespace

void ErrorByEyeLayers::errorJson(nlohmann::json& error) const {
  nlohmann::json list = nlohmann::json::array();
  for (const LayerBucket& b : buckets) {
    nlohmann::json j = {{"layers", {b.lo, b.hi}}, {"pixels", b.pixels}};
    if (b.imageMeanAbs) j["image_mean_abs"] = *b.imageMeanAbs;
    if (b.flipMean) j["flip_mean"] = *b.flipMean;
    if (b.visibilityMeanAbs) j["visibility_mean_abs"] = *b.visibilityMeanAbs;
    list.push_back(j);
  }
  error["by_eye_layers"] = list;
}

}  // namespace sb

SB_MEASURE({.name = "by_eye_layers",
            .help = "with a reference: the error over the pixels of each bucket of eye depth "
                    "complexity, 0, 1, 2-3, 4-7, ... (error.by_eye_layers)",
            .measure = sb::measure});
