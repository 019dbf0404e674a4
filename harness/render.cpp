#include "harness/render.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <sstream>

#include "backends/device.h"
#include "backends/window.h"
#include "harness/invariants.h"
#include "harness/metrics.h"
#include "harness/settings.h"
#include "harness/stop.h"
#include "reports/stats.h"
#include "techniques/frame/renderer.h"

namespace sb {

namespace {
// A light of `type` fitted to the scene, then moved to the given direction
// and position (a point light given only a position looks at the scene's centre).
Light placeLight(const Bounds& b, LightType type, const std::optional<glm::vec3>& direction,
                 const std::optional<glm::vec3>& position) {
  Light l = fitLight(b, type);
  if (direction) {
    l.direction = glm::normalize(*direction);
    if (type == LightType::Directional)
      l.position = b.center() - l.direction * (2.0f * b.radius() + 1e-6f);
  }
  if (position) {
    l.position = *position;
    if (!direction && glm::length(b.center() - l.position) > 0)
      l.direction = glm::normalize(b.center() - l.position);
  }
  if (direction || position) fitLightFrustum(l, b);
  return l;
}
}  // namespace

RenderSettings makeRenderSettings(const RenderRequest& req, const Scene& scene) {
  checkRequest(req, Spelling::Cli);  // every value in its range: the checks below are the fit's
  RenderSettings s;
  s.width = req.width;
  s.height = req.height;
  s.primitive = req.primitive == "ribbons" ? Primitive::Ribbons : Primitive::Lines;
  s.ribbonWidth = req.ribbonWidth;
  s.shading = ShadingModel::fromSpec(req.shading);
  s.msaa = static_cast<uint32_t>(req.msaa);

  const Bounds b = scene.bounds();
  const ViewOverrides& o = req.view;
  s.camera = fitCamera(b, static_cast<float>(req.width) / static_cast<float>(req.height));
  if (o.cameraEye) s.camera.eye = *o.cameraEye;
  if (o.cameraTarget) s.camera.target = *o.cameraTarget;
  if (o.cameraUp) s.camera.up = *o.cameraUp;
  if (o.cameraEye || o.cameraTarget) fitCameraPlanes(s.camera, b);  // keep the scene inside
  if (o.fov) s.camera.fovYDegrees = *o.fov;
  if (o.nearPlane) s.camera.nearPlane = *o.nearPlane;
  if (o.farPlane) s.camera.farPlane = *o.farPlane;
  // A plane given beside a fitted one can still cross it.
  if (!(s.camera.farPlane > s.camera.nearPlane))
    throw InputError("camera planes need near < far (near " + std::to_string(s.camera.nearPlane) +
                     ", far " + std::to_string(s.camera.farPlane) + ")");
  if (glm::length(s.camera.target - s.camera.eye) <= 0)
    throw InputError("camera eye and target coincide");

  s.light = placeLight(b, o.lightType == "point" ? LightType::Point : LightType::Directional,
                       o.lightDirection, o.lightPosition);
  if (o.lightColor) s.light.color = *o.lightColor;
  if (o.lightIntensity) s.light.intensity = *o.lightIntensity;
  for (const ExtraLight& e : req.extraLights) {
    const bool point = e.type == "point";
    Light l = placeLight(b, point ? LightType::Point : LightType::Directional,
                         point ? std::nullopt : std::optional(e.at),
                         point ? std::optional(e.at) : std::nullopt);
    l.color = e.color;
    l.intensity = e.intensity;
    s.extraLights.push_back(l);
  }
  return s;
}

namespace {

nlohmann::json boundsJson(const Bounds& b) {
  return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
}

VisibilityError visibilityError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  auto floats = [](const std::vector<uint8_t>& bytes) {
    std::vector<float> v(bytes.size() / sizeof(float));
    std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
    return v;
  };
  return compareVisibility(floats(a), floats(b));
}

nlohmann::json visibilityJson(const VisibilityError& e) {
  return {{"rmse", e.rmse}, {"max", e.max}, {"pixels", e.pixels}};
}

// `error` of the report: {image (with an image), visibility, total, own}.
nlohmann::json errorJson(const RenderResult& r) {
  nlohmann::json error;
  if (r.imageError) error["image"] = toJson(*r.imageError);
  if (r.flip) error["image"]["flip"] = toJson(*r.flip);
  if (r.visibilityError) error["visibility"] = visibilityJson(*r.visibilityError);
  // `image` and `visibility` above are the total error, kept under their old
  // keys for the readers of earlier result files (baselines, compare-runs).
  nlohmann::json total;
  if (error.contains("image")) total["image"] = error["image"];
  if (error.contains("visibility")) total["visibility"] = error["visibility"];
  error["total"] = total;
  if (r.own) {
    const OwnError& o = *r.own;
    nlohmann::json own = {{"technique", o.technique},
                          {"reference", {{"shadow", o.referenceShadow}, {"oit", o.referenceOit}}}};
    if (o.image) own["image"] = toJson(*o.image);
    if (o.flipMean) own["image"]["flip"] = {{"mean", *o.flipMean}};
    if (o.visibility) own["visibility"] = visibilityJson(*o.visibility);
    error["own"] = own;
  }
  if (!r.errorByEyeLayers.empty()) {
    nlohmann::json buckets = nlohmann::json::array();
    for (const LayerBucket& b : r.errorByEyeLayers) {
      nlohmann::json j = {{"layers", {b.lo, b.hi}}, {"pixels", b.pixels}};
      if (b.imageMeanAbs) j["image_mean_abs"] = *b.imageMeanAbs;
      if (b.flipMean) j["flip_mean"] = *b.flipMean;
      if (b.visibilityMeanAbs) j["visibility_mean_abs"] = *b.visibilityMeanAbs;
      buckets.push_back(j);
    }
    error["by_eye_layers"] = buckets;
  }
  return error;
}

nlohmann::json animationJson(const AnimationResult& a) {
  nlohmann::json frames = nlohmann::json::array();
  for (const AnimationFrame& f : a.frames) {
    nlohmann::json j = {
        {"frame", f.frame}, {"degrees", f.degrees}, {"visibility", {{"rmse", f.visibilityRmse}}}};
    if (f.imageRmse) j["image"] = {{"rmse", *f.imageRmse}, {"flip", *f.flipMean}};
    frames.push_back(j);
  }
  nlohmann::json flicker = {{"visibility", a.visibilityFlicker},
                            {"visibility_pixels", a.visibilityPixels}};
  if (a.imageFlicker) flicker["image"] = *a.imageFlicker;
  return {{"kind", a.spec.kind}, {"frames", a.spec.frames}, {"degrees", a.spec.degrees},
          {"flicker", flicker},  {"per_frame", frames},     {"strip_frames", a.stripFrames}};
}

nlohmann::json complexityJson(const std::optional<DepthComplexity>& c) {
  if (!c) return nullptr;
  return {{"max", c->max}, {"mean", c->mean}, {"fragments", c->total}};
}

// The host memory the final image takes after the frames: the RGBA32F rows
// read back and the image made of them, both held at once.
std::size_t imageHostBytes(const RenderSettings& s) {
  return std::size_t{s.width} * s.height * 4 * sizeof(float) * 2;
}

Image colorImage(Renderer& r, const RenderSettings& s) {
  const std::vector<uint8_t> rows = r.readColor();  // names itself when out of memory
  try {
    Image img = imageFromRows(rows, static_cast<int>(s.width), static_cast<int>(s.height),
                              PixelType::Float32, 4);
    for (std::size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
    return img;
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory making the " + std::to_string(s.width) + "x" +
                           std::to_string(s.height) + " RGBA float image from the read back, " +
                           std::to_string(rows.size()) + " bytes: a host allocation failed");
  }
}

// The reference for a technique: exact shadows at the technique's light-map
// size (visibility is per light texel) and exact transparency. Both use the
// sorted fragment lists: the tests prove them identical to depth peeling,
// which needs three passes per layer.
const char* kReferenceOit = "abuffer";

Spec referenceShadowSpec(const Spec& shadow) {
  Spec ref;
  ref.name = "exact";
  ref.options["method"] = "abuffer";
  auto size = shadow.options.find("size");
  if (size != shadow.options.end()) ref.options["size"] = size->second;
  return ref;
}

}  // namespace

std::unique_ptr<Device> makeRequestDevice(const RenderRequest& req) {
  // checkRequest names a bad backend or platform as the front end spells it;
  // these are for requests built in code.
  const std::vector<std::string> platforms = platformNames(req.backend);
  if (platforms.empty()) throw InputError("unknown backend '" + req.backend + "'");
  DeviceOptions dopts;
  dopts.backend = req.backend;
  dopts.platform = req.platform.empty() ? platforms.front() : req.platform;
  dopts.validation = req.validation;
  dopts.windowWidth = req.width;
  dopts.windowHeight = req.height;
  dopts.windowTitle = "strandbench render: " + req.scene + " shadow " + req.shadow + " oit " +
                      req.oit + " (" + req.backend + ")";
  if (std::find(platforms.begin(), platforms.end(), dopts.platform) == platforms.end())
    throw InputError("--platform " + dopts.platform + " is not a " + req.backend + " platform");
  return createDevice(dopts);
}

std::vector<glm::vec3> probeRay(const Light& light, const ProbeSpec& probe,
                                std::vector<float>& depths) {
  const glm::mat4 inv = glm::inverse(light.projection() * light.view());
  const glm::vec2 ndc = (glm::vec2(probe.texel) + 0.5f) / float(probe.mapSize) * 2.0f - 1.0f;
  std::vector<glm::vec3> points;
  for (int i = 0; i < probe.samples; ++i) {
    const float z = (float(i) + 0.5f) / float(probe.samples);
    const glm::vec4 w = inv * glm::vec4(ndc, z, 1.0f);
    points.push_back(glm::vec3(w) / w.w);
    depths.push_back(z);
  }
  return points;
}

namespace {

std::shared_ptr<const Scene> sceneFor(const std::string& spec, RenderCache* cache) {
  if (cache) {
    auto it = cache->scenes.find(spec);
    if (it != cache->scenes.end()) return it->second;
  }
  auto scene = std::make_shared<const Scene>(makeScene(Spec::parse(spec)));
  if (cache) cache->scenes[spec] = scene;
  return scene;
}

// Everything the reference's pixels depend on.
std::string referenceKey(const RenderRequest& req, const RenderSettings& s, const Spec& refShadow) {
  std::ostringstream k;
  k.precision(9);
  auto v3 = [&](const glm::vec3& v) { k << v.x << "," << v.y << "," << v.z << ";"; };
  k << req.backend << "|" << req.platform << "|" << req.scene << "|" << s.width << "x" << s.height
    << "|" << req.primitive << "|" << req.ribbonWidth << "|" << refShadow.str() << "|";
  v3(s.camera.eye);
  v3(s.camera.target);
  v3(s.camera.up);
  k << s.camera.fovYDegrees << "," << s.camera.nearPlane << "," << s.camera.farPlane << "|"
    << int(s.light.type) << ";";
  v3(s.light.position);
  v3(s.light.direction);
  v3(s.light.color);
  k << s.light.intensity << "|";
  for (const Light& l : s.extraLights) {
    k << int(l.type) << ";";
    v3(l.position);
    v3(l.direction);
    v3(l.color);
    k << l.intensity << "|";
  }
  k << req.image;
  if (req.probe)
    k << "|probe " << req.probe->texel.x << "," << req.probe->texel.y << "," << req.probe->mapSize
      << "," << req.probe->samples;
  return k.str();
}

std::string mib(std::size_t b) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f MiB", double(b) / (1 << 20));
  return text;
}

// Refuses a run whose resources would not fit, before they are made: over
// --memory-limit (`limit`, all of the timed frames' resources) or over the
// device's budget (what is left of it for the resources not made yet). The
// message lists the largest resources and what would make the run fit.
// `host`: host memory the run takes besides its resources (the image read
// back), counted against the budget only: --memory-limit and the reported
// estimate are the device's bytes.
void checkMemory(const std::vector<ResourceBytes>& planned, const std::vector<ResourceBytes>& made,
                 long long limit, const MemoryBudget& budget, const std::string& what,
                 std::size_t host = 0) {
  std::size_t total = 0, already = 0;
  for (const auto& r : planned) total += r.bytes;
  for (const auto& r : made) already += r.bytes;
  const std::size_t toMake = (total > already ? total - already : 0) + host;
  std::string over;
  std::size_t fit = 0, need = total;  // the bytes the run would have to fit in, and needs
  if (limit > 0 && total > static_cast<std::size_t>(limit)) {
    over = "over the memory limit (--memory-limit " + std::to_string(limit) + ")";
    fit = static_cast<std::size_t>(limit);
  } else if (budget.bytes && toMake > budget.bytes) {
    over = "over the device's budget: " + std::to_string(budget.bytes) + " bytes (" +
           mib(budget.bytes) + ") left, from " + budget.source;
    if (host) over += "; with " + mib(host) + " of host memory for the image read back";
    fit = budget.bytes + already;
    need = total + host;
  } else {
    return;
  }
  std::vector<ResourceBytes> largest = planned;
  if (need > total)  // over the budget, which counts the host's image
    largest.push_back({"image read back", "host", host});
  std::sort(largest.begin(), largest.end(),
            [](const ResourceBytes& a, const ResourceBytes& b) { return a.bytes > b.bytes; });
  std::string m = "memory: " + what + " needs " + std::to_string(total) + " bytes (" + mib(total) +
                  "), " + over +
                  "; refused before they were made (made so far: " + std::to_string(already) +
                  " bytes), nothing written. Largest resources:";
  for (std::size_t i = 0; i < largest.size() && i < 8; ++i)
    m += "\n  " + largest[i].name + " (" + largest[i].owner + "): " + mib(largest[i].bytes);
  const double shrink = double(need) / double(fit);
  char factor[64] = "";
  if (shrink > 1.0) std::snprintf(factor, sizeof factor, " (%.1fx less memory)", shrink);
  m += std::string("\nTo fit") + factor +
       ": a smaller --size (frame and fragment lists scale with its pixels), a smaller map "
       "size= (light maps and lists scale with its texels), or fewer layers=, maps=, slices=.";
  throw OutOfMemoryError(m);
}

// checkMemory for every resource a run makes until it goes (Device::setMemoryGuard).
class RunMemoryGuard {
 public:
  RunMemoryGuard(Device& dev, long long limit, const MemoryBudget& budget) : dev_(dev) {
    dev_.setMemoryGuard(
        [&dev, limit, budget](const std::vector<ResourceBytes>& planned, const std::string& what) {
          checkMemory(planned, dev.allocations(), limit, budget, what);
        });
  }
  ~RunMemoryGuard() { dev_.setMemoryGuard(nullptr); }
  RunMemoryGuard(const RunMemoryGuard&) = delete;
  RunMemoryGuard& operator=(const RunMemoryGuard&) = delete;

 private:
  Device& dev_;
};

// The progress line of a render and the stop check, between the device's
// passes: a frame of depth peeling is hundreds of passes and can take minutes.
class RenderProgress {
 public:
  explicit RenderProgress(Device& dev) : dev_(dev), line_("render") {
    dev_.setPassObserver([this](const std::string& pass) { onPass(pass); });
  }
  ~RenderProgress() { dev_.setPassObserver(nullptr); }
  RenderProgress(const RenderProgress&) = delete;
  RenderProgress& operator=(const RenderProgress&) = delete;

  // A new piece of work ("frame 3/10"); `layers` from the counting pass (0: none).
  void phase(std::string text, uint32_t layers = 0) {
    if (passes_) lastPasses_ = passes_;
    phase_ = std::move(text);
    layers_ = layers;
    passes_ = layer_ = 0;
    throwIfStopped();
  }

 private:
  void onPass(const std::string& pass) {
    throwIfStopped();
    ++passes_;
    // Both peeling loops (peel, exact method=peel) end a layer with their
    // ".advance" dispatch.
    if (pass.size() > 8 && pass.compare(pass.size() - 8, 8, ".advance") == 0) ++layer_;
    std::string text = phase_ + ", pass " + std::to_string(passes_);
    if (lastPasses_) text += "/" + std::to_string(lastPasses_);
    if (layer_) {
      text += ", layer " + std::to_string(layer_);
      if (layers_) text += " of up to " + std::to_string(layers_);
    }
    line_.update(text + ": " + pass);
  }

  Device& dev_;
  ProgressLine line_;
  std::string phase_ = "setup";
  uint32_t layers_ = 0, layer_ = 0;
  std::size_t passes_ = 0, lastPasses_ = 0;
};

uint32_t peelLayers(const std::optional<DepthComplexity>& c) { return c ? c->max : 0; }

RenderCache::Reference renderReference(Device& dev, const Scene& scene,
                                       const RenderSettings& settings, const Spec& refShadow,
                                       const RenderRequest& req) {
  std::set<std::string> outputs = {"visibility"};
  if (req.image) outputs.insert("color");
  if (req.probe) outputs.insert("probe");
  // The reference is exact at each pixel's centre: one sample, whatever
  // --msaa the run has (its error then includes what anti-aliasing changed).
  RenderSettings exactSettings = settings;
  exactSettings.msaa = 1;
  Renderer ref(dev, scene, exactSettings, refShadow, Spec::parse(kReferenceOit), outputs);
  checkMemory(dev.allocationsAfterUsing(ref.graphResources(outputs)), dev.allocations(), 0,
              dev.memoryBudget(), "the reference", req.image ? imageHostBytes(settings) : 0);
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

nlohmann::json statsJson(const std::vector<double>& samples) {
  const Stats s = summarize(samples);
  return {{"median", s.median}, {"min", s.min},       {"max", s.max},
          {"mean", s.mean},     {"stddev", s.stddev}, {"samples", samples}};
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
        if (kind != "total" && kind != "own" &&
            kind != "by_eye_layers" &&  // copies and objects, checked apart
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

}  // namespace

std::size_t RenderResult::bytesOwnedBy(const std::string& owner) const {
  std::size_t bytes = 0;
  for (const auto& r : resources)
    if (r.owner == owner) bytes += r.bytes;
  return bytes;
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
  std::set<std::string> outputs = {"visibility"};
  if (req.image) outputs.insert("color");

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

// Which light a pass or resource is (Renderer::lightPrefix): an extra light's
// index, else 0 (the key light); -1 for the sum of the lights.
int lightOfName(const std::string& name, std::size_t lights) {
  if (name == "lights.sum") return -1;
  for (std::size_t i = 1; i < lights; ++i)
    if (name.rfind(Renderer::lightPrefix(i), 0) == 0) return static_cast<int>(i);
  return 0;
}

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
    if (i < 0 || (i == 0 && res.owner == "scene")) continue;
    shares[i].bytes += res.bytes;
    if (res.owner == "shadow") shares[i].shadowBytes += res.bytes;
  }
  return shares;
}

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
    Renderer r(dev, scene, own, o.shadow, o.oit, {"color"});
    r.renderFrame();
    fresh = colorImage(r, own);
    image = cache ? &(cache->ownReferences[key] = std::move(fresh)) : &fresh;
  }
  e.image = compareImages(out.image, *image);
  e.flipMean = computeFlip(out.image, *image).mean;
  return e;
}

}  // namespace

RenderResult runRender(const RenderRequest& req, RenderCache* cache, Device* device) {
  checkRequest(req, Spelling::Cli);
  const std::shared_ptr<const Scene> scenePtr = sceneFor(req.scene, cache);
  const Scene& scene = *scenePtr;
  const Spec shadowSpec = Spec::parse(req.shadow);
  const Spec oitSpec = Spec::parse(req.oit);
  // Unknown names and options are refused before any device is made.
  makeShadowTechnique(shadowSpec);
  makeOitTechnique(oitSpec);
  RenderSettings settings = makeRenderSettings(req, scene);
  std::vector<float> probeDepths;
  if (req.probe) settings.probePoints = probeRay(settings.light, *req.probe, probeDepths);

  std::unique_ptr<Device> ownDevice = device ? nullptr : makeRequestDevice(req);
  Device* const dev = device ? device : ownDevice.get();
  if (!dev->supportsSamples(settings.msaa))
    throw InputError(settingMessage(*findSetting("msaa"), Spelling::Cli,
                                    std::to_string(settings.msaa),
                                    "the device has " + dev->sampleCountsText() +
                                        " samples per pixel (" + dev->info().device + ")"));
  RenderProgress progress(*dev);

  // The timed frames produce what the run is for: the shaded image, or (for a
  // visibility-only run) the visibility image. Error measurements run after
  // them in untimed frames.
  const std::set<std::string> timed = {req.image ? "color" : "visibility"};
  std::set<std::string> outputs = timed;
  if (req.reference) outputs.insert("visibility");
  if (req.probe) outputs.insert("probe");
  // The limit and the budget hold from the first resource on: the renderer's
  // preparations (counting passes and their maps) run before the plan below.
  const MemoryBudget budget = dev->memoryBudget();
  std::optional<RunMemoryGuard> guard;
  guard.emplace(*dev, req.memoryLimit, budget);
  Renderer renderer(*dev, scene, settings, shadowSpec, oitSpec, outputs);
  // What the timed frames will hold, known before their resources are made.
  RenderResult out;
  const auto planned = dev->allocationsAfterUsing(renderer.graphResources(timed));
  for (const auto& r : planned) out.estimatedBytes += r.bytes;
  checkMemory(planned, dev->allocations(), req.memoryLimit, budget, "this run",
              req.image ? imageHostBytes(settings) : 0);
  const uint32_t layers = std::max(peelLayers(renderer.oit().depthComplexity()),
                                   peelLayers(renderer.shadow().depthComplexity()));
  // A window platform shows every frame, warm-up included; the timed frames
  // time the present apart from the passes.
  Window* window = device ? nullptr : dev->window();
  if (window) out.presented = RenderResult::Presented{0, dev->info().present, {}, {}};
  auto present = [&](PresentedImage* capture) {
    const auto start = std::chrono::steady_clock::now();
    const bool shown = dev->present(renderer.colorTexture(), capture);
    window->poll();  // keep the window system answered
    return std::pair{
        shown, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                   .count()};
  };
  for (int i = 0; i < req.warmup; ++i) {
    progress.phase("warm-up frame " + std::to_string(i + 1) + "/" + std::to_string(req.warmup),
                   layers);
    renderer.renderFrame(timed);
    if (window) present(nullptr);
  }

  for (int i = 0; i < req.repeat; ++i) {
    progress.phase("frame " + std::to_string(i + 1) + "/" + std::to_string(req.repeat), layers);
    double total = 0;
    for (const auto& t : renderer.renderFrame(timed)) {
      auto pass = std::find_if(out.passes.begin(), out.passes.end(),
                               [&](const PassTimes& p) { return p.name == t.name; });
      if (pass == out.passes.end()) pass = out.passes.insert(out.passes.end(), {t.name, 0, {}});
      pass->ms.push_back(t.ms);
      pass->executions = t.executions;
      total += t.ms;
    }
    out.frameMs.push_back(total);
    if (window) {
      const auto [shown, ms] = present(nullptr);
      out.presented->frames += shown ? 1 : 0;
      out.presented->ms.push_back(ms);
    }
  }
  if (window && req.image) {
    PresentedImage shown;
    if (present(&shown).first && !shown.rgba8.empty()) {
      Image img =
          imageFromRows(shown.rgba8, int(shown.width), int(shown.height), PixelType::UNorm8, 4);
      for (std::size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
      out.presented->image = std::move(img);
    }
  }

  if (req.image) out.image = colorImage(renderer, settings);
  // Memory of this run's techniques only (before any reference is built).
  out.resources = dev->allocations();
  guard.reset();  // the measurements and references that follow are not the run's own
  out.pipelines = renderer.compiledPipelines();
  out.preparations = renderer.preparations();
  std::sort(out.resources.begin(), out.resources.end(),
            [](const ResourceBytes& a, const ResourceBytes& b) { return a.name < b.name; });
  out.warnings = scene.warnings;  // the input's, then the techniques'
  for (const auto& w : renderer.warnings()) out.warnings.push_back(w);
  out.counters = renderer.counters();
  // Either technique's emulation (the shadow's, then the transparency's).
  for (const std::string& why :
       {renderer.shadow().timingEmulated(), renderer.oit().timingEmulated()})
    if (!why.empty()) out.timingEmulated += (out.timingEmulated.empty() ? "" : "; ") + why;
  if (!out.timingEmulated.empty())
    out.warnings.push_back("timing emulated, not a real cost: " + out.timingEmulated);

  out.device = dev->info();
  out.scene = {req.scene,
               scene.strands.strandCount(),
               scene.strands.points.size(),
               scene.strands.segmentCount(),
               scene.mesh.triangleCount(),
               scene.bounds()};
  out.shadow = shadowSpec.str();
  out.oit = oitSpec.str();
  out.shading = settings.shading.spec;
  out.primitive = req.primitive;
  out.width = settings.width;
  out.height = settings.height;
  out.repeat = req.repeat;
  out.warmup = req.warmup;
  out.graph = renderer.graphPasses(timed);
  out.lights = lightShares(settings, out);

  out.eyeComplexity = renderer.oit().depthComplexity();
  out.lightComplexity = renderer.shadow().depthComplexity();
  std::set<std::string> measured;
  if (req.reference && req.image) measured.insert("visibility");  // else the timed frames made it
  if (req.probe) measured.insert("probe");
  if (!measured.empty()) {
    out.measurementGraph = renderer.graphPasses(measured);
    progress.phase("measurement frame", layers);
    renderer.renderFrame(measured);
  }
  if (req.reference || req.probe) {
    const Spec refShadow = referenceShadowSpec(shadowSpec);
    const std::string key = referenceKey(req, settings, refShadow);
    RenderCache::Reference fresh;
    const RenderCache::Reference* ref = nullptr;
    if (cache && cache->references.count(key)) {
      ref = &cache->references.at(key);
    } else {
      progress.phase("reference");
      fresh = renderReference(*dev, scene, settings, refShadow, req);
      if (cache) {
        ++cache->referenceRenders;
        ref = &(cache->references[key] = std::move(fresh));
      } else {
        ref = &fresh;
      }
    }
    for (const auto& w : ref->warnings) out.warnings.push_back(w);
    if (!out.eyeComplexity) out.eyeComplexity = ref->eye;
    if (!out.lightComplexity) out.lightComplexity = ref->light;
    out.reference = {refShadow.str(), kReferenceOit};
    if (req.reference) {
      if (req.image) {
        out.referenceImage = ref->image;
        out.imageError = compareImages(out.image, out.referenceImage);
        // The image as its PNG shows it: display values (harness/flip.h).
        out.flip = computeFlip(out.image, out.referenceImage);
      }
      out.visibility = renderer.readVisibility();
      out.visibilityError = visibilityError(out.visibility, ref->visibility);
      if (ref->eye) out.errorByEyeLayers = errorByLayers(out, *ref->eye, ref->visibility);
      out.own = ownError(req, *dev, scene, settings, shadowSpec, oitSpec, refShadow, out, cache);
      if (req.animate)
        out.animation =
            runAnimation(req, scene, settings, shadowSpec, oitSpec, refShadow, out, *ref);
    }
    if (req.probe)
      out.probe = ProbeResult{req.probe->texel, req.probe->mapSize, probeDepths, ref->probe,
                              renderer.readProbe()};
    if (req.invariants)
      out.invariants = checkInvariants(req, out, settings, renderer, *dev, ref->probe);
  }
  if (req.validation) out.validationMessages = validationMessageCount();
  return out;
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

nlohmann::json renderJson(const RenderResult& r) {
  nlohmann::json j;
  j["backend"] = r.device.backend;
  j["platform"] = r.device.platform;
  j["device"] = r.device.device;
  j["driver"] = r.device.driver;
  j["timing"] = r.device.timing;
  j["lines"] = r.device.lines;
  j["scene"] = {{"spec", r.scene.spec},
                {"strands", r.scene.strands},
                {"points", r.scene.points},
                {"segments", r.scene.segments},
                {"mesh_triangles", r.scene.meshTriangles},
                {"bounds", boundsJson(r.scene.bounds)}};
  j["shadow"] = r.shadow;
  j["oit"] = r.oit;
  j["shading"] = r.shading;
  j["primitive"] = r.primitive;
  j["size"] = {r.width, r.height};
  j["repeat"] = r.repeat;
  j["warmup"] = r.warmup;
  j["graph"] = r.graph;
  nlohmann::json pipelines = nlohmann::json::array();
  for (const auto& [name, technique] : r.pipelines)
    pipelines.push_back({{"name", name}, {"technique", technique}});
  j["build"] = {{"pipelines", pipelines}, {"preparations", r.preparations}};
  j["passes"] = nlohmann::json::array();
  for (const PassTimes& p : r.passes)
    j["passes"].push_back(
        {{"name", p.name}, {"executions", p.executions}, {"ms", statsJson(p.ms)}});
  j["frame_ms"] = statsJson(r.frameMs);

  nlohmann::json resources = nlohmann::json::array();
  std::size_t total = 0;
  for (const auto& res : r.resources) {
    resources.push_back({{"name", res.name}, {"owner", res.owner}, {"bytes", res.bytes}});
    total += res.bytes;
  }
  j["memory"] = {{"shadow_bytes", r.bytesOwnedBy("shadow")},
                 {"oit_bytes", r.bytesOwnedBy("oit")},
                 {"scene_bytes", r.bytesOwnedBy("scene")},
                 {"frame_bytes", r.bytesOwnedBy("frame")},
                 {"total_bytes", total},
                 {"estimated_bytes", r.estimatedBytes},
                 {"resources", resources}};

  if (!r.lights.empty()) {
    auto v3 = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    nlohmann::json lights = nlohmann::json::array();
    for (std::size_t i = 0; i < r.lights.size(); ++i) {
      const Light& l = r.lights[i].light;
      const bool point = l.type == LightType::Point;
      lights.push_back({{"light", i + 1},
                        {"type", point ? "point" : "directional"},
                        {point ? "position" : "direction", v3(point ? l.position : l.direction)},
                        {"color", v3(l.color)},
                        {"intensity", l.intensity},
                        {"prefix", Renderer::lightPrefix(i)},
                        {"ms", statsJson(r.lights[i].ms)},
                        {"shadow_bytes", r.lights[i].shadowBytes},
                        {"bytes", r.lights[i].bytes}});
    }
    j["lights"] = lights;
  }
  if (r.measurementGraph) j["measurement_graph"] = *r.measurementGraph;
  if (r.reference) j["reference"] = {{"shadow", r.reference->first}, {"oit", r.reference->second}};
  if (r.visibilityError) j["error"] = errorJson(r);
  if (r.animation) j["animation"] = animationJson(*r.animation);
  if (r.probe)
    j["probe"] = {{"texel", {r.probe->texel.x, r.probe->texel.y}},
                  {"map_size", r.probe->mapSize},
                  {"light_depth", r.probe->lightDepth},
                  {"exact", r.probe->exact},
                  {"visibility", r.probe->visibility}};
  if (r.invariants) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& f : *r.invariants) list.push_back({{"pass", f.pass}, {"what", f.what}});
    j["invariants"] = {{"failures", list}};
  }
  if (r.eyeComplexity || r.lightComplexity)
    j["depth_complexity"] = {{"eye", complexityJson(r.eyeComplexity)},
                             {"light", complexityJson(r.lightComplexity)}};
  j["warnings"] = r.warnings;
  if (!r.counters.empty()) {
    nlohmann::json counters = nlohmann::json::object();
    for (const Counter& c : r.counters) counters[c.name] = c.value;
    j["counters"] = counters;
  }
  if (!r.timingEmulated.empty()) j["timing_emulated"] = r.timingEmulated;
  if (r.validationMessages) j["validation_messages"] = *r.validationMessages;
  if (r.presented) {
    // frame_ms plus the present: the frame time with presentation included.
    std::vector<double> withPresent = r.frameMs;
    for (std::size_t i = 0; i < withPresent.size() && i < r.presented->ms.size(); ++i)
      withPresent[i] += r.presented->ms[i];
    j["presented"] = {{"frames", r.presented->frames},
                      {"how", r.presented->how},
                      {"present_ms", statsJson(r.presented->ms)},
                      {"frame_ms", statsJson(withPresent)}};
  }
  return j;
}

}  // namespace sb
