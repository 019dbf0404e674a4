// --reference aa:samples=S: the anti-aliased exact reference and the error against it
// (error.aa), docs/ground-truth.md "The anti-aliased reference": the exact shadows and
// transparency at S x S samples per pixel and per light texel, strands with their true
// width, box-filtered to the image's size.
#include <chrono>
#include <string>

#include "backends/device.h"
#include "harness/reference_spec.h"
#include "harness/render_steps.h"
#include "render/frame/renderer.h"
#include "render/graph/frame_planner.h"

namespace sb {

namespace {

constexpr int kMaxAaSamples = 8;
// The largest image and light map side (the size setting's range, 16384: what
// the drivers' textures take).
constexpr uint64_t kMaxSide = 16384;

std::string sizeText(uint64_t w, uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

// The mean of each samples x samples block (the image's size divided by samples).
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

// The samples and light map side of the aa reference at `samples`.
struct AaSides {
  uint64_t width, height, lightSize;
};

struct AaReference : Reference {
  int samples = 4;  // per pixel along each axis (S x S per pixel)

  std::string str() const override;

  // InputError when a side is over kMaxSide.
  AaSides sides(const RenderSettings& settings, const Spec& refShadow) const {
    const uint64_t s = static_cast<uint64_t>(samples);
    // The exact shadow's light map at `samples` times its side: samples x samples
    // per texel of the aliased reference's map, so light and eye are sampled alike.
    const AaSides a{settings.width * s, settings.height * s,
                    uint64_t(referenceLightMap(refShadow).size) * s};
    if (a.width > kMaxSide || a.height > kMaxSide || a.lightSize > kMaxSide)
      throw InputError("reference '" + str() + "' renders " + sizeText(a.width, a.height) +
                       " samples with a light map of " + sizeText(a.lightSize, a.lightSize) +
                       " texels: over the largest side, " + std::to_string(kMaxSide) +
                       "; give a smaller --size, a smaller map size= or fewer samples=");
    return a;
  }

  void check(const RenderSettings& settings, const Spec& refShadow) const override {
    sides(settings, refShadow);
  }

  RenderResult::MoreReference render(const ReferenceInputs& in) const override;
};

const OptionTable<AaReference> kOptions({opt::integer(&AaReference::samples, "samples", 4, 1,
                                                      kMaxAaSamples,
                                                      "samples per pixel along each axis, 1..8")});

std::string AaReference::str() const { return "aa:samples=" + std::to_string(samples); }

RenderResult::MoreReference AaReference::render(const ReferenceInputs& in) const {
  const RenderSettings& settings = in.settings;
  const auto start = std::chrono::steady_clock::now();
  RenderResult::MoreReference m;
  m.name = "aa";
  m.samples = samples;
  m.spec = str();
  const AaSides a = sides(settings, in.refShadow);
  const uint64_t w = a.width, h = a.height, size = a.lightSize;
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
  const Spec shadow = withLightMapSize(in.refShadow, static_cast<uint32_t>(size));
  m.width = hi.width;
  m.height = hi.height;
  m.lightSize = static_cast<uint32_t>(size);

  // A device of its own: its memory is its own (measured, and freed when it goes).
  const std::unique_ptr<Device> dev = makeRequestDevice(in.req);
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
  Renderer r(d, in.scene, hi, shadow, Spec::parse(kReferenceOit), {Output::Color});
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

}  // namespace

}  // namespace sb

SB_REFERENCE({.name = "aa",
              .help = "the anti-aliased exact reference: the same at samples x samples per pixel "
                      "and per light texel, strands drawn with their true width, box-filtered "
                      "(error.aa)",
              .example = "aa:samples=2",
              .options = kOptions.infos(),
              .make = [](const OptionReader& reader) {
                return std::make_shared<const AaReference>(kOptions.read(reader));
              }});
