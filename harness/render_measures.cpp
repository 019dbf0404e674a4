// What a render measures after its timed frames (harness/render_steps.h): the exact
// reference, the errors against it (total, own, by eye layers, over an animation), the
// light shares and the invariants.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <set>

#include "backends/device.h"
#include "harness/invariants.h"
#include "harness/render_steps.h"
#include "harness/stop.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "render/graph/frame_planner.h"

namespace sb {

VisibilityError visibilityError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  auto floats = [](const std::vector<uint8_t>& bytes) {
    std::vector<float> v(bytes.size() / sizeof(float));
    std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
    return v;
  };
  return compareVisibility(floats(a), floats(b));
}

const char* kReferenceOit = "abuffer";

Spec referenceShadowSpec(const Spec& shadow) {
  Spec ref;
  ref.name = "exact";
  ref.options["method"] = "abuffer";
  auto size = shadow.options.find("size");
  if (size != shadow.options.end()) ref.options["size"] = size->second;
  // A jittered lookup (occupancy's jitter=on) is judged against the exact maps looked up with
  // the same jitter: the same sampling of the light map, as the same size is.
  // Unjittered, the reference stays the one every other technique has ("exact", one key).
  if (auto it = shadow.options.find("jitter"); it != shadow.options.end() && it->second == "on") {
    ref.options["jitter"] = "on";
    if (auto n = shadow.options.find("jitter_samples"); n != shadow.options.end())
      ref.options["jitter_samples"] = n->second;
  }
  return ref;
}

RenderCache::Reference renderReference(Device& dev, const Scene& scene,
                                       const RenderSettings& settings, const Spec& refShadow,
                                       const RenderRequest& req) {
  Outputs outputs = {Output::Visibility};
  if (req.image) outputs.insert(Output::Color);
  if (req.probe) outputs.insert(Output::Probe);
  // The reference is exact at each pixel's centre: one sample, whatever
  // --msaa the run has (its error then includes what anti-aliasing changed).
  RenderSettings exactSettings = settings;
  exactSettings.msaa = 1;
  Renderer ref(dev, scene, exactSettings, refShadow, Spec::parse(kReferenceOit), outputs);
  checkMemory(FramePlanner::of(dev).allocationsAfterUsing(ref.graphResources(outputs)),
              dev.allocations(), 0, dev.memoryBudget(), "the reference",
              req.image ? imageHostBytes(settings) : 0);
  ref.renderFrame();
  RenderCache::Reference r;
  if (req.image) r.image = colorImage(ref, settings);
  r.visibility = ref.readVisibility();
  if (req.probe) r.probe = ref.readProbe();
  r.eye = ref.oit().depthComplexity();
  r.light = ref.shadow().depthComplexity();
  for (auto& w : ref.warnings()) r.warnings.push_back("reference: " + w);
  return r;
}

// The invariants of a finished run (harness/invariants.h), the reported errors included.
std::vector<InvariantFailure> checkInvariants(const RenderRequest& req, const RenderResult& out,
                                              const RenderSettings& settings, Renderer& renderer,
                                              Device& dev, const std::vector<float>& exactProbe) {
  std::vector<InvariantFailure> failures;
  if (req.image) {
    const std::string last = out.graph.empty() ? "" : out.graph.back();
    checkColor(out.image, HairShading::maxRadiance(settings), last, failures);
  }
  if (req.reference) {
    checkVisibility(out.visibility, "visibility", failures);
    const nlohmann::json errors = errorJson(out);  // named: items() of a temporary dangles
    for (const auto& [kind, e] : errors.items())
      for (const auto& [metric, v] : e.items())
        // PSNR is infinite (null) exactly when the images are identical.
        if (kind != "own" && kind != "by_eye_layers" &&  // copies and objects, checked apart
            ((v.is_null() && !(metric == "psnr" && e.value("identical", false))) ||
             (v.is_number_float() && !std::isfinite(v.get<double>()))))
          failures.push_back({"reference", "error " + kind + "." + metric + " is not a number"});
    if (out.flip && !(out.flip->min >= 0.0 && out.flip->max <= 1.0))
      failures.push_back({"reference", "error image.flip outside [0, 1]"});
  }
  if (req.probe) {
    checkRay(out.probe->visibility, "probe (" + Spec::parse(req.shadow).name + ")", failures,
             renderer.shadow().monotone());
    checkRay(exactProbe, "probe (reference)", failures);
  }
  for (Texture t : renderer.shadow().lookup().inputs.sampled()) {
    const TextureDesc d = dev.describe(t);
    checkMap(dev.readTexture(t), d.format, "map " + d.name, failures);
  }
  return failures;
}

namespace {

// Frame `frame` of an animation: the light turned about the scene's centre, or
// the camera about its target, about the camera's up axis.
RenderSettings animatedSettings(const RenderSettings& base, const RenderRequest& req,
                                const Bounds& b, int frame, double& degrees) {
  const AnimateSpec& a = *req.animate;
  degrees = a.degrees * frame / double(a.frames - 1);
  const glm::mat4 turn4 =
      glm::rotate(glm::mat4(1.0f), glm::radians(float(degrees)), glm::normalize(base.camera.up));
  const glm::mat3 turn(turn4);
  RenderSettings s = base;
  if (a.kind == "light-orbit") {
    s.light.direction = glm::normalize(turn * base.light.direction);
    s.light.position = b.center() + turn * (base.light.position - b.center());
    fitLightFrustum(s.light, b);
  } else {
    s.camera.eye = s.camera.target + turn * (base.camera.eye - base.camera.target);
    // Fitted planes follow the eye; planes the request gave stay.
    if (!req.view.nearPlane && !req.view.farPlane) fitCameraPlanes(s.camera, b);
  }
  return s;
}

// Mean over pixels and RGB of |(t1 - t0) - (r1 - r0)|, accumulated.
void addImageFlicker(const Image& t0, const Image& t1, const Image& r0, const Image& r1,
                     double& sum, std::size_t& count) {
  const int c = t0.channels;
  for (std::size_t p = 0; p + c <= t0.pixels.size(); p += c)
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = p + k;
      sum += std::fabs(double(t1.pixels[i] - t0.pixels[i]) - double(r1.pixels[i] - r0.pixels[i]));
      ++count;
    }
}

std::vector<float> visibilityFloats(const std::vector<uint8_t>& bytes) {
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
  return v;
}

// The same over the pixels where all four visibility images see a surface (>= 0).
void addVisibilityFlicker(const std::vector<float>& t0, const std::vector<float>& t1,
                          const std::vector<float>& r0, const std::vector<float>& r1, double& sum,
                          std::size_t& count) {
  for (std::size_t i = 0; i < t0.size(); ++i) {
    if (t0[i] < 0 || t1[i] < 0 || r0[i] < 0 || r1[i] < 0) continue;
    sum += std::fabs(double(t1[i] - t0[i]) - double(r1[i] - r0[i]));
    ++count;
  }
}

// Frames of the report's strip: up to four, evenly spaced, the first and last included.
std::vector<int> stripFrames(int frames) {
  std::vector<int> f;
  const int n = std::min(frames, 4);
  for (int i = 0; i < n; ++i) {
    const int k = static_cast<int>(std::lround(double(i) * (frames - 1) / (n - 1)));
    if (f.empty() || f.back() != k) f.push_back(k);
  }
  return f;
}
}  // namespace

// Frames 1 .. N-1 of an animation, each by the technique and by the reference;
// frame 0 is the still render already in `out` and `ref`.
AnimationResult runAnimation(const RenderRequest& req, const Scene& scene,
                             const RenderSettings& settings, const Spec& shadowSpec,
                             const Spec& oitSpec, const Spec& refShadow, const RenderResult& out,
                             const RenderCache::Reference& ref) {
  AnimationResult a;
  a.spec = *req.animate;
  a.stripFrames = stripFrames(a.spec.frames);
  RenderRequest refReq = req;
  refReq.probe.reset();
  Outputs outputs = {Output::Visibility};
  if (req.image) outputs.insert(Output::Color);

  Image prevT = out.image, prevR = out.referenceImage;
  std::vector<float> prevVT = visibilityFloats(out.visibility);
  std::vector<float> prevVR = visibilityFloats(ref.visibility);
  double imageSum = 0, visSum = 0;
  std::size_t imageCount = 0, visCount = 0;
  auto keep = [&](int frame, const Image& t, const Image& r) {
    if (req.image &&
        std::find(a.stripFrames.begin(), a.stripFrames.end(), frame) != a.stripFrames.end()) {
      a.stripImages.push_back(t);
      a.stripReferences.push_back(r);
    }
  };
  AnimationFrame first{0, 0.0, std::nullopt, std::nullopt, out.visibilityError->rmse};
  if (req.image) {
    first.imageRmse = out.imageError->rmse;
    first.flipMean = out.flip->mean;
  }
  a.frames.push_back(first);
  keep(0, prevT, prevR);
  for (int t = 1; t < a.spec.frames; ++t) {
    throwIfStopped();  // each frame has its own device, without the progress observer
    AnimationFrame f;
    f.frame = t;
    const RenderSettings st = animatedSettings(settings, req, scene.bounds(), t, f.degrees);
    // A device per frame: a device frees its resources only when it goes, so
    // the frames' memory stays that of one frame (declared before the renderer,
    // which it outlives).
    const std::unique_ptr<Device> dev = makeRequestDevice(req);
    Renderer r(*dev, scene, st, shadowSpec, oitSpec, outputs);
    r.renderFrame();
    Image img;
    if (req.image) img = colorImage(r, st);
    const std::vector<float> vis = visibilityFloats(r.readVisibility());
    const RenderCache::Reference fr = renderReference(*dev, scene, st, refShadow, refReq);
    const std::vector<float> refVis = visibilityFloats(fr.visibility);
    f.visibilityRmse = compareVisibility(vis, refVis).rmse;
    addVisibilityFlicker(prevVT, vis, prevVR, refVis, visSum, visCount);
    if (req.image) {
      f.imageRmse = compareImages(img, fr.image).rmse;
      f.flipMean = computeFlip(img, fr.image).mean;
      addImageFlicker(prevT, img, prevR, fr.image, imageSum, imageCount);
      keep(t, img, fr.image);
      prevT = std::move(img);
      prevR = fr.image;
    }
    prevVT = vis;
    prevVR = refVis;
    a.frames.push_back(f);
  }
  if (req.image) a.imageFlicker = imageCount ? imageSum / double(imageCount) : 0.0;
  a.visibilityFlicker = visCount ? visSum / double(visCount) : 0.0;
  a.visibilityPixels = visCount;
  return a;
}

// Buckets 0, 1, 2-3, 4-7, ... of eye layers; errors averaged per bucket.
std::vector<LayerBucket> errorByLayers(const RenderResult& out, const DepthComplexity& eye,
                                       const std::vector<uint8_t>& referenceVisibility) {
  const std::size_t w = out.width, h = out.height;
  std::vector<LayerBucket> buckets;
  if (eye.counts.size() != w * h) return buckets;
  auto bucketOf = [](uint32_t n) { return n == 0 ? 0 : 1 + int(std::bit_width(n)) - 1; };
  const std::vector<float> vt = visibilityFloats(out.visibility);
  const std::vector<float> vr = visibilityFloats(referenceVisibility);
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
    buckets.push_back(k);
  }
  return buckets;
}
namespace {

// Which light a pass or resource is (Renderer::lightPrefix): an extra light's
// index, else 0 (the key light); -1 for the sum of the lights.
int lightOfName(const std::string& name, std::size_t lights) {
  if (name == "lights.sum") return -1;
  for (std::size_t i = 1; i < lights; ++i)
    if (name.rfind(Renderer::lightPrefix(i), 0) == 0) return static_cast<int>(i);
  return 0;
}
}  // namespace

std::vector<RenderResult::LightShare> lightShares(const RenderSettings& s, const RenderResult& r) {
  if (s.extraLights.empty()) return {};
  std::vector<RenderResult::LightShare> shares(1 + s.extraLights.size());
  for (std::size_t i = 0; i < shares.size(); ++i) {
    shares[i].light = i == 0 ? s.light : s.extraLights[i - 1];
    shares[i].ms.assign(r.frameMs.size(), 0.0);
  }
  for (const PassTimes& p : r.passes) {
    const int i = lightOfName(p.name, shares.size());
    if (i < 0) continue;
    for (std::size_t f = 0; f < p.ms.size() && f < shares[i].ms.size(); ++f)
      shares[i].ms[f] += p.ms[f];
  }
  for (const ResourceBytes& res : r.resources) {
    const int i = lightOfName(res.name, shares.size());
    if (i < 0 || (i == 0 && res.owner == Owner::Scene)) continue;
    shares[i].bytes += res.bytes;
    if (res.owner == Owner::Shadow) shares[i].shadowBytes += res.bytes;
  }
  return shares;
}
namespace {

// Which technique a case's own error judges, and its reference: exact in the
// other family only (README "Ground truth and error").
struct OwnReference {
  std::string technique;
  Spec shadow, oit;
};
OwnReference ownReference(const Spec& shadowSpec, const Spec& oitSpec, const Spec& refShadow) {
  if (oitSpec.name != "none") return {"transparency", shadowSpec, Spec::parse(kReferenceOit)};
  return {"shadow", refShadow, oitSpec};
}
}  // namespace

// The case's own error (OwnError), its reference rendered once per sweep.
OwnError ownError(const RenderRequest& req, Device& dev, const Scene& scene,
                  const RenderSettings& settings, const Spec& shadowSpec, const Spec& oitSpec,
                  const Spec& refShadow, const RenderResult& out, RenderCache* cache) {
  const OwnReference o = ownReference(shadowSpec, oitSpec, refShadow);
  OwnError e;
  e.technique = o.technique;
  e.referenceShadow = o.shadow.str();
  e.referenceOit = o.oit.str();
  if (o.technique == "shadow") e.visibility = out.visibilityError;
  if (!req.image) return e;
  // Exact transparency is exact at pixel centres: one sample, as the full reference.
  RenderSettings own = settings;
  if (o.technique == "transparency") own.msaa = 1;
  const std::string key = referenceKey(req, settings, o.shadow) + "|own " + o.shadow.str() + " " +
                          o.oit.str() + "|msaa " + std::to_string(own.msaa);
  Image fresh;
  const Image* image = nullptr;
  if (o.shadow.str() == refShadow.str() && o.oit.str() == kReferenceOit) {
    image = &out.referenceImage;  // exact in both families: the full reference
  } else if (cache && cache->ownReferences.count(key)) {
    image = &cache->ownReferences.at(key);
  } else {
    Renderer r(dev, scene, own, o.shadow, o.oit, {Output::Color});
    r.renderFrame();
    fresh = colorImage(r, own);
    image = cache ? &(cache->ownReferences[key] = std::move(fresh)) : &fresh;
  }
  e.image = compareImages(out.image, *image);
  e.flipMean = computeFlip(out.image, *image).mean;
  return e;
}

Image animationStrip(const AnimationResult& a) {
  if (a.stripImages.empty()) return {};
  const int gap = 2, w = a.stripImages[0].width, h = a.stripImages[0].height;
  const int n = static_cast<int>(a.stripImages.size());
  Image strip(n * w + (n - 1) * gap, 2 * h + gap, 4, 1.0f);
  auto place = [&](const Image& img, int x0, int y0) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c)
          strip.pixels[(std::size_t(y0 + y) * strip.width + x0 + x) * 4 + c] =
              c < img.channels ? img.pixels[(std::size_t(y) * w + x) * img.channels + c] : 1.0f;
  };
  for (int i = 0; i < n; ++i) {
    place(a.stripImages[i], i * (w + gap), 0);
    place(a.stripReferences[i], i * (w + gap), h + gap);
  }
  return strip;
}

}  // namespace sb
