// The further references of a render (RenderRequest::references,
// harness/reference_spec.h): each rendered by its unit (harness/references/<name>/), on a
// device of its own or on the CPU, and compared with the image here (error.<name>'s core
// fields), once per sweep.
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "harness/reference_spec.h"
#include "harness/render_steps.h"
#include "imaging/metrics.h"

namespace sb {

namespace {

double meanRgb(const Image& im) {
  double sum = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < 3; ++c) sum += im.pixels[im.index(x, y, c)];
  return im.width && im.height ? sum / (3.0 * im.width * im.height) : 0.0;
}

// The least-squares exposure scale of `image` against `ref` over pixels and RGB, and the
// RMSE at that scale (1 and the plain RMSE for a black image).
std::pair<double, double> bestScale(const Image& image, const Image& ref) {
  double ir = 0, ii = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double a = image.pixels[image.index(x, y, c)], b = ref.pixels[ref.index(x, y, c)];
        ir += a * b;
        ii += a * a;
      }
  const double scale = ii > 0 ? ir / ii : 1.0;
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double d =
            scale * image.pixels[image.index(x, y, c)] - ref.pixels[ref.index(x, y, c)];
        sum += d * d;
      }
  const double n = 3.0 * image.width * image.height;
  return {scale, n > 0 ? std::sqrt(sum / n) : 0.0};
}

}  // namespace

void checkMoreReferences(const RenderRequest& req, const RenderSettings& settings,
                         const Spec& refShadow) {
  for (const std::string& text : req.references)
    parseReferenceSpec(text).unit->check(settings, refShadow);
}

std::vector<RenderResult::MoreReference> moreReferences(
    const RenderRequest& req, const Scene& scene, const RenderSettings& settings,
    const Spec& refShadow, const RenderResult& out, RenderCache* cache) {
  std::vector<RenderResult::MoreReference> list;
  for (const std::string& text : req.references) {
    const ReferenceSpec spec = parseReferenceSpec(text);
    if (spec.name == defaultReference().name) continue;  // already rendered with the run
    const std::string key = referenceKey(req, settings, refShadow) + "|" + spec.str();
    RenderResult::MoreReference m;
    if (cache && cache->moreReferences.count(key)) {
      m = cache->moreReferences.at(key);
      m.cached = true;
    } else {
      m = spec.unit->render({req, scene, settings, refShadow});
      if (cache) cache->moreReferences[key] = m;
    }
    m.image = compareImages(out.image, m.referenceImage);
    m.flip = computeFlip(out.image, m.referenceImage);
    m.imageMean = meanRgb(out.image);
    m.referenceMean = meanRgb(m.referenceImage);
    std::tie(m.bestScale, m.scaledRmse) = bestScale(out.image, m.referenceImage);
    list.push_back(std::move(m));
  }
  return list;
}

}  // namespace sb
