// The animation measure (animation.h): frames 1 .. N-1 of the orbit, each on a device of its
// own, by the technique and by the reference; frame 0 is the run's still render.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "harness/measures/animation/animation.h"
#include "harness/measures/measure_unit.h"
#include "harness/render_steps.h"
#include "harness/stop.h"
#include "render/frame/renderer.h"

namespace sb {
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
// Frames 1 .. N-1 of an animation, each by the technique and by the reference;
// frame 0 is the still render already in `out` and `ref`.
std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  const RenderRequest& req = in.req;
  if (!req.animate || !req.reference || !in.reference) return nullptr;
  const RenderResult& out = in.out;
  const RenderCache::Reference& ref = *in.reference;
  auto result = std::make_shared<AnimationResult>();
  AnimationResult& a = *result;
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
    const RenderSettings st = animatedSettings(in.settings, req, in.scene.bounds(), t, f.degrees);
    // A device per frame: a device frees its resources only when it goes, so
    // the frames' memory stays that of one frame (declared before the renderer,
    // which it outlives).
    const std::unique_ptr<Device> dev = makeRequestDevice(req);
    Renderer r(*dev, in.scene, st, in.shadow, in.oit, outputs);
    r.renderFrame();
    Image img;
    if (req.image) img = colorImage(r, st);
    const std::vector<float> vis = visibilityFloats(r.readVisibility());
    const RenderCache::Reference fr = renderReference(*dev, in.scene, st, in.refShadow, refReq);
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
  return result;
}

}  // namespace

void AnimationResult::json(nlohmann::json& report) const {
  nlohmann::json list = nlohmann::json::array();
  for (const AnimationFrame& f : frames) {
    nlohmann::json j = {
        {"frame", f.frame}, {"degrees", f.degrees}, {"visibility", {{"rmse", f.visibilityRmse}}}};
    if (f.imageRmse) j["image"] = {{"rmse", *f.imageRmse}, {"flip", *f.flipMean}};
    list.push_back(j);
  }
  nlohmann::json flicker = {{"visibility", visibilityFlicker},
                            {"visibility_pixels", visibilityPixels}};
  if (imageFlicker) flicker["image"] = *imageFlicker;
  report["animation"] = {{"kind", spec.kind},       {"frames", spec.frames},
                         {"degrees", spec.degrees}, {"flicker", flicker},
                         {"per_frame", list},       {"strip_frames", stripFrames}};
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

SB_MEASURE({.name = "animation",
            .help = "with --animate and a reference: each frame of the orbit by the technique "
                    "and by the reference, its error, and the flicker",
            .measure = sb::measure});
