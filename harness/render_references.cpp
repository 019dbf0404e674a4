// The further references of a render (RenderRequest::references,
// harness/reference_spec.h): the anti-aliased exact reference and the error
// against it (error.aa), docs/ground-truth.md "The anti-aliased reference"; the
// CPU strand references (error.pbr, harness/pbr_reference.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

#include "backends/device.h"
#include "harness/pbr_reference.h"
#include "harness/reference_spec.h"
#include "harness/render_steps.h"
#include "imaging/metrics.h"
#include "render/common/unit.h"
#include "render/frame/renderer.h"
#include "render/graph/frame_planner.h"
#include "techniques/exact/exact.h"

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

namespace {

// The largest image and light map side (the size setting's range, 16384: what
// the drivers' textures take).
constexpr uint64_t kMaxSide = 16384;

std::string sizeText(uint64_t w, uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

Image boxFilter(const Image& image, int samples) {
  const int s = samples, w = image.width / s, h = image.height / s, c = image.channels;
  Image out(w, h, c, 0.0f);
  const double weight = 1.0 / (double(s) * double(s));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) {
        double sum = 0;
        for (int j = 0; j < s; ++j)
          for (int i = 0; i < s; ++i) sum += image.pixels[image.index(x * s + i, y * s + j, k)];
        out.pixels[out.index(x, y, k)] = static_cast<float>(sum * weight);
      }
  return out;
}

namespace {

// The samples and light map side of the aa reference at `samples`; InputError
// when a side is over kMaxSide.
struct AaSides {
  uint64_t width, height, lightSize;
};
AaSides aaSides(const RenderSettings& settings, const Spec& refShadow, int samples) {
  const uint64_t s = static_cast<uint64_t>(samples);
  // The exact shadow's light map at `samples` times its side: samples x samples
  // per texel of the aliased reference's map, so light and eye are sampled alike.
  const AaSides a{settings.width * s, settings.height * s,
                  uint64_t(ExactShadow::optionsOf(refShadow).size) * s};
  if (a.width > kMaxSide || a.height > kMaxSide || a.lightSize > kMaxSide)
    throw InputError("reference '" + ReferenceSpec{"aa", samples}.str() + "' renders " +
                     sizeText(a.width, a.height) + " samples with a light map of " +
                     sizeText(a.lightSize, a.lightSize) + " texels: over the largest side, " +
                     std::to_string(kMaxSide) +
                     "; give a smaller --size, a smaller map size= or fewer samples=");
  return a;
}

}  // namespace

void checkMoreReferences(const RenderRequest& req, const RenderSettings& settings,
                         const Spec& refShadow) {
  for (const std::string& text : req.references) {
    const ReferenceSpec spec = parseReferenceSpec(text);
    if (spec.name == "aa") aaSides(settings, refShadow, spec.samples);
  }
}

RenderResult::MoreReference renderAaReference(const RenderRequest& req, const Scene& scene,
                                              const RenderSettings& settings, const Spec& refShadow,
                                              int samples) {
  const auto start = std::chrono::steady_clock::now();
  RenderResult::MoreReference m;
  m.name = "aa";
  m.samples = samples;
  m.spec = ReferenceSpec{"aa", samples}.str();
  const AaSides sides = aaSides(settings, refShadow, samples);
  const uint64_t w = sides.width, h = sides.height, size = sides.lightSize;
  RenderSettings hi = settings;
  hi.width = static_cast<uint32_t>(w);
  hi.height = static_cast<uint32_t>(h);
  hi.msaa = 1;
  hi.probePoints.clear();
  // Strands with their true width: a line is one pixel (texel) wide, a ribbon
  // ribbon_width pixels; at samples times the resolution they are samples
  // times as wide, drawn as ribbons (a line's width cannot be set the same way
  // on both APIs).
  // World strands keep their world width (and coverage) at any resolution.
  if (settings.primitive != Primitive::World) {
    hi.ribbonWidth = (settings.primitive == Primitive::Lines ? 1.0f : settings.ribbonWidth) *
                     static_cast<float>(samples);
    hi.primitive = Primitive::Ribbons;
  }
  Spec shadow = refShadow;
  shadow.options["size"] = std::to_string(size);
  m.width = hi.width;
  m.height = hi.height;
  m.lightSize = static_cast<uint32_t>(size);

  // A device of its own: its memory is its own (measured, and freed when it goes).
  const std::unique_ptr<Device> dev = makeRequestDevice(req);
  const MemoryBudget budget = dev->memoryBudget();
  // The read back (RGBA32F rows and the image made of them) and the filtered image.
  m.hostBytes = imageHostBytes(hi) + std::size_t{settings.width} * settings.height * 16;
  const std::string what = "the anti-aliased reference (" + m.spec + ": " + sizeText(w, h) +
                           " samples, light maps " + sizeText(size, size) + ")";
  Device& d = *dev;
  auto check = [&d, &budget, &what, &m](const std::vector<ResourceBytes>& planned) {
    try {
      checkMemory(planned, d.allocations(), 0, budget, what, m.hostBytes);
    } catch (const OutOfMemoryError& e) {
      throw OutOfMemoryError(std::string(e.what()) +
                             " Its memory grows with samples^2: fewer samples= would fit sooner.");
    }
  };
  FramePlanner& planner = FramePlanner::of(d);
  planner.setMemoryGuard(
      [&check](const std::vector<ResourceBytes>& planned, const std::string&) { check(planned); });
  struct Unguard {
    FramePlanner& p;
    ~Unguard() { p.setMemoryGuard(nullptr); }
  } unguard{planner};
  Renderer r(d, scene, hi, shadow, Spec::parse(kReferenceOit), {Output::Color});
  check(planner.allocationsAfterUsing(r.graphResources({Output::Color})));
  for (const PassTime& t : r.renderFrame()) m.frameMs += t.ms;
  for (const ResourceBytes& b : d.allocations()) m.bytes += b.bytes;
  for (const std::string& warning : r.warnings())
    m.warnings.push_back("reference " + m.spec + ": " + warning);
  m.referenceImage = boxFilter(colorImage(r, hi), samples);
  m.wallMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return m;
}

std::vector<RenderResult::MoreReference> moreReferences(
    const RenderRequest& req, const Scene& scene, const RenderSettings& settings,
    const Spec& refShadow, const RenderResult& out, RenderCache* cache) {
  std::vector<RenderResult::MoreReference> list;
  for (const std::string& text : req.references) {
    const ReferenceSpec spec = parseReferenceSpec(text);
    if (spec.name == "exact") continue;  // the default reference, already rendered
    const std::string key = referenceKey(req, settings, refShadow) + "|" + spec.str();
    RenderResult::MoreReference m;
    if (cache && cache->moreReferences.count(key)) {
      m = cache->moreReferences.at(key);
      m.cached = true;
    } else {
      m = spec.name == "pbr" ? renderPbrReference(scene, settings, refShadow, spec)
                             : renderAaReference(req, scene, settings, refShadow, spec.samples);
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
