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
#include "harness/measures/measure_unit.h"
#include "harness/render_steps.h"
#include "harness/settings.h"
#include "harness/stop.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "render/graph/frame_planner.h"
#include "reports/stats.h"

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
  s.primitive = req.primitive == "ribbons" ? Primitive::Ribbons
                : req.primitive == "world" ? Primitive::World
                                           : Primitive::Lines;
  s.ribbonWidth = req.ribbonWidth;
  s.geometry = req.geometry == "compute" ? GeometryPath::Compute
               : req.geometry == "mesh"  ? GeometryPath::Mesh
                                         : GeometryPath::Cpu;
  s.shading = ShadingModel::fromSpec(req.shading);
  s.msaa = static_cast<uint32_t>(req.msaa);

  const Bounds b = scene.bounds();
  const ViewOverrides& o = req.view;
  s.camera = fitCamera(b, static_cast<float>(req.width) / static_cast<float>(req.height),
                       scene.frameByBox);
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
  // World strands without a thickness of their own: one pixel at the scene's centre, the
  // path-traced reference's width for them too.
  if (s.primitive == Primitive::World)
    s.worldThickness = static_cast<float>(pixelAtSceneCentre(scene, s));
  return s;
}

float worldPixelAt(const glm::mat4& proj, const glm::mat4& viewProj, glm::vec3 p, float side) {
  const float w = (viewProj * glm::vec4(p, 1.0f)).w;
  return 2.0f * std::abs(w) / (std::abs(proj[1][1]) * side);
}

double pixelAtSceneCentre(const Scene& scene, const RenderSettings& s) {
  const glm::mat4 proj = s.camera.projection(float(s.width) / float(s.height));
  return worldPixelAt(proj, proj * s.camera.view(), scene.bounds().center(), float(s.height));
}

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

}  // namespace

std::string referenceKey(const RenderRequest& req, const RenderSettings& s, const Spec& refShadow) {
  std::ostringstream k;
  k.precision(9);
  auto v3 = [&](const glm::vec3& v) { k << v.x << "," << v.y << "," << v.z << ";"; };
  k << req.backend << "|" << req.platform << "|" << req.scene << "|" << s.width << "x" << s.height
    << "|" << req.primitive << "|" << req.ribbonWidth << "|" << refShadow.str() << "|"
    << (req.image ? req.shading : "") << "|";  // its image is shaded with the case's model
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

namespace {

std::string mib(std::size_t b) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f MiB", double(b) / (1 << 20));
  return text;
}

}  // namespace

void checkMemory(const std::vector<ResourceBytes>& planned, const std::vector<ResourceBytes>& made,
                 long long limit, const MemoryBudget& budget, const std::string& what,
                 std::size_t host) {
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
    largest.push_back({"image read back", Owner::Host, host});
  auto bigger = [](const ResourceBytes& a, const ResourceBytes& b) { return a.bytes > b.bytes; };
  std::stable_sort(largest.begin(), largest.end(), bigger);
  // The same bytes by owner: what each part of the run takes, and what shrinks it.
  std::vector<ResourceBytes> owners;
  for (const auto& r : largest) {
    auto o = std::find_if(owners.begin(), owners.end(),
                          [&](const ResourceBytes& x) { return x.owner == r.owner; });
    if (o == owners.end()) o = owners.insert(owners.end(), {ownerName(r.owner), r.owner, 0});
    o->bytes += r.bytes;
  }
  std::stable_sort(owners.begin(), owners.end(), bigger);
  std::string m = "memory: " + what + " needs " + std::to_string(need) + " bytes (" + mib(need) +
                  "), " + over +
                  "; refused before they were made (made so far: " + std::to_string(already) +
                  " bytes), nothing written.\nBy owner:";
  for (const auto& o : owners)
    m += " " + o.name + " " + mib(o.bytes) + " (" +
         std::to_string(need ? (o.bytes * 100 + need / 2) / need : 0) + "%);";
  m.back() = '.';
  m += "\nLargest resources:";
  for (std::size_t i = 0; i < largest.size() && i < 8; ++i)
    m += "\n  " + largest[i].name + " (" + ownerName(largest[i].owner) +
         "): " + mib(largest[i].bytes);
  char factor[96];
  std::snprintf(factor, sizeof factor, "%.1fx less memory: %s needed, %s allowed",
                fit ? double(need) / double(fit) : 0.0, mib(need).c_str(), mib(fit).c_str());
  m += std::string("\nTo fit (") + factor + "), shrink";
  static const std::map<Owner, std::string> kAdvice = {
      {Owner::Shadow,
       "the shadow technique's maps and lists: a smaller map size= (they scale with its "
       "texels) or fewer of its maps=, layers= or slices="},
      {Owner::Oit,
       "the transparency technique's lists and targets: a smaller --size (they scale with its "
       "pixels and depth complexity)"},
      {Owner::Frame, "the frame's targets: a smaller --size (they scale with its pixels)"},
      {Owner::Host, "the image read back: a smaller --size"},
      {Owner::Scene, "the scene: fewer strands or points"}};
  for (const auto& o : owners) {
    const auto advice = kAdvice.find(o.owner);
    if (advice == kAdvice.end() || o.bytes * 20 < need) continue;  // under 5%: cannot help much
    m += "\n  " + advice->second + " (" + mib(o.bytes) + ")";
    // Where the rest alone is over, this owner is not enough by itself.
    if (need - o.bytes > fit)
      m += "; the rest alone needs " + mib(need - o.bytes) + ", so not this alone";
  }
  throw OutOfMemoryError(m);
}

namespace {

// checkMemory for every resource a run makes until it goes (FramePlanner::setMemoryGuard).
class RunMemoryGuard {
 public:
  RunMemoryGuard(Device& dev, long long limit, const MemoryBudget& budget)
      : planner_(FramePlanner::of(dev)) {
    planner_.setMemoryGuard(
        [&dev, limit, budget](const std::vector<ResourceBytes>& planned, const std::string& what) {
          checkMemory(planned, dev.allocations(), limit, budget, what);
        });
  }
  ~RunMemoryGuard() { planner_.setMemoryGuard(nullptr); }
  RunMemoryGuard(const RunMemoryGuard&) = delete;
  RunMemoryGuard& operator=(const RunMemoryGuard&) = delete;

 private:
  FramePlanner& planner_;
};

// The progress line of a render and the stop check, between the device's
// passes: a frame of depth peeling is hundreds of passes and can take minutes.
class RenderProgress {
 public:
  explicit RenderProgress(Device& dev) : planner_(FramePlanner::of(dev)), line_("render") {
    planner_.setPassObserver([this](const std::string& pass) { onPass(pass); });
  }
  ~RenderProgress() { planner_.setPassObserver(nullptr); }
  RenderProgress(const RenderProgress&) = delete;
  RenderProgress& operator=(const RenderProgress&) = delete;

  // A new piece of work ("frame 3/10"); `layers` from the counting pass (0: none).
  // `frame`: a warm-up or timed frame, which does the same passes as the frame before
  // it, so that one's count is this one's total; other work (setup, the reference) has
  // passes of its own, with no total known.
  void phase(std::string text, uint32_t layers = 0, bool frame = false) {
    lastPasses_ = frame && frame_ ? passes_ : 0;
    frame_ = frame;
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
    if (lastPasses_ >= passes_) text += "/" + std::to_string(lastPasses_);
    if (layer_) {
      text += ", layer " + std::to_string(layer_);
      if (layers_) text += " of up to " + std::to_string(layers_);
    }
    line_.update(text + ": " + pass);
  }

  FramePlanner& planner_;
  ProgressLine line_;
  std::string phase_ = "setup";
  uint32_t layers_ = 0, layer_ = 0;
  std::size_t passes_ = 0, lastPasses_ = 0;
  bool frame_ = false;  // the current phase is a warm-up or timed frame
};

uint32_t peelLayers(const std::optional<DepthComplexity>& c) { return c ? c->max : 0; }

// runRender's stages, in order. Each takes what the ones before made.

// 1. Validate: everything the request names, before any device is made.
struct Validated {
  // The scene drawn and the full model it is made from: the same scene unless
  // it has a level of detail, chosen for the view (withLevelOfDetail).
  std::shared_ptr<const Scene> scene, full;
  Spec shadow, oit;
  RenderSettings settings;
  std::vector<float> probeDepths;
};

Validated validate(const RenderRequest& req, RenderCache* cache) {
  checkRequest(req, Spelling::Cli);
  Validated v;
  v.full = sceneFor(req.scene, cache);
  v.shadow = Spec::parse(req.shadow);
  v.oit = Spec::parse(req.oit);
  // Unknown names and options are refused here, not by a half-made renderer.
  makeShadowTechnique(v.shadow);
  makeOitTechnique(v.oit);
  v.settings = makeRenderSettings(req, *v.full);  // the camera fits the full model
  v.scene = v.full->groom.hasLod() ? std::make_shared<const Scene>(withLevelOfDetail(
                                         *v.full, v.settings.camera, v.settings.height))
                                   : v.full;
  if (req.probe) v.settings.probePoints = probeRay(v.settings.light, *req.probe, v.probeDepths);
  checkMoreReferences(req, v.settings, referenceShadowSpec(v.shadow));
  return v;
}

// 2. Device: the caller's, or one made for this run; then what only it can refuse.
struct RunDevice {
  std::unique_ptr<Device> owned;
  Device* dev = nullptr;
  Window* window = nullptr;  // a window platform of the run's own device
};

RunDevice openDevice(const RenderRequest& req, const RenderSettings& settings, Device* given) {
  RunDevice d;
  if (!given) d.owned = makeRequestDevice(req);
  d.dev = given ? given : d.owned.get();
  if (!given) d.window = d.dev->window();
  if (!d.dev->supportsSamples(settings.msaa))
    throw InputError(settingMessage(*findSetting("msaa"), Spelling::Cli,
                                    std::to_string(settings.msaa),
                                    "the device has " + d.dev->sampleCountsText() +
                                        " samples per pixel (" + d.dev->info().device + ")"));
  if (settings.geometry == GeometryPath::Mesh)
    if (const std::string why = d.dev->meshPipelineRefusal(); !why.empty())
      throw UnavailableError(settingMessage(*findSetting("geometry"), Spelling::Cli, "mesh", why),
                             "Mesa 25.0's lavapipe: --driver mesa-25.0 (scripts/drivers.sh)");
  return d;
}

// 3. Plan: the renderer (its culled graph) and the memory check of what the timed
// frames will hold, before their resources are made. The limit and the budget
// hold from the first resource on: the renderer's preparations (counting passes
// and their maps) come before the plan.
struct Plan {
  // The timed frames produce what the run is for: the shaded image, or (for a
  // visibility-only run) the visibility image. Error measurements run after
  // them in untimed frames.
  Outputs timed;
  std::unique_ptr<RunMemoryGuard> guard;
  std::unique_ptr<Renderer> renderer;
  uint32_t layers = 0;  // the most layers a peeling loop will take (progress)
};

Plan plan(const RenderRequest& req, const Validated& v, Device& dev, RenderResult& out) {
  Plan p;
  p.timed = {req.image ? Output::Color : Output::Visibility};
  Outputs outputs = p.timed;
  if (req.reference) outputs.insert(Output::Visibility);
  if (req.probe) outputs.insert(Output::Probe);
  const MemoryBudget budget = dev.memoryBudget();
  p.guard = std::make_unique<RunMemoryGuard>(dev, req.memoryLimit, budget);
  p.renderer = std::make_unique<Renderer>(dev, *v.scene, v.settings, v.shadow, v.oit, outputs);
  const auto planned =
      FramePlanner::of(dev).allocationsAfterUsing(p.renderer->graphResources(p.timed));
  for (const auto& r : planned) out.estimatedBytes += r.bytes;
  checkMemory(planned, dev.allocations(), req.memoryLimit, budget, "this run",
              req.image ? imageHostBytes(v.settings) : 0);
  p.layers = std::max(peelLayers(p.renderer->oit().depthComplexity()),
                      peelLayers(p.renderer->shadow().depthComplexity()));
  return p;
}

// 4. Frames: warm-up, then the timed frames, pass by pass. A window platform shows
// every frame, warm-up included; the timed frames time the present apart.
void frames(const RenderRequest& req, Plan& p, const RunDevice& d, RenderProgress& progress,
            RenderResult& out) {
  Renderer& renderer = *p.renderer;
  if (d.window) out.presented = RenderResult::Presented{0, d.dev->info().present, {}, {}};
  auto present = [&](PresentedImage* capture) {
    const auto start = std::chrono::steady_clock::now();
    const bool shown = d.dev->present(renderer.colorTexture(), capture);
    d.window->poll();  // keep the window system answered
    return std::pair{
        shown, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                   .count()};
  };
  for (int i = 0; i < req.warmup; ++i) {
    progress.phase("warm-up frame " + std::to_string(i + 1) + "/" + std::to_string(req.warmup),
                   p.layers, true);
    renderer.renderFrame(p.timed);
    if (d.window) present(nullptr);
  }
  for (int i = 0; i < req.repeat; ++i) {
    progress.phase("frame " + std::to_string(i + 1) + "/" + std::to_string(req.repeat), p.layers,
                   true);
    double total = 0;
    for (const auto& t : renderer.renderFrame(p.timed)) {
      auto pass = std::find_if(out.passes.begin(), out.passes.end(),
                               [&](const PassTimes& pt) { return pt.name == t.name; });
      if (pass == out.passes.end())
        pass = out.passes.insert(out.passes.end(), {t.name, t.owner, 0, {}, t.work});
      // Work is exact: a timed frame that did other work than the first is named.
      if (!pass->ms.empty() && !(t.work == pass->work) &&
          std::find(out.workVaries.begin(), out.workVaries.end(), t.name) == out.workVaries.end())
        out.workVaries.push_back(t.name);
      pass->ms.push_back(t.ms);
      pass->executions = t.executions;
      total += t.ms;
    }
    out.frameMs.push_back(total);
    if (req.timeline) out.timeline.push_back(renderer.lastTimings());
    if (d.window) {
      const auto [shown, ms] = present(nullptr);
      out.presented->frames += shown ? 1 : 0;
      out.presented->ms.push_back(ms);
    }
  }
  if (d.window && req.image) {
    PresentedImage shown;
    if (present(&shown).first && !shown.rgba8.empty()) {
      Image img =
          imageFromRows(shown.rgba8, int(shown.width), int(shown.height), PixelType::UNorm8, 4);
      for (std::size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
      out.presented->image = std::move(img);
    }
  }
}

// 5. Outputs: what the timed frames made (the image, this run's resources, its
// warnings and counters) and what the run was. Ends the memory guard: what
// follows is measurement, not the run's own.
void outputs(const RenderRequest& req, const Validated& v, Plan& p, Device& dev,
             RenderResult& out) {
  Renderer& renderer = *p.renderer;
  const Scene& scene = *v.scene;
  if (req.image) out.image = colorImage(renderer, v.settings);
  out.resources = dev.allocations();  // before any reference is built
  p.guard.reset();
  out.pipelines = renderer.compiledPipelines();
  out.preparations = renderer.preparations();
  std::sort(out.resources.begin(), out.resources.end(),
            [](const ResourceBytes& a, const ResourceBytes& b) { return a.name < b.name; });
  out.warnings = scene.warnings;  // the input's, then the techniques'
  for (const auto& w : renderer.warnings()) out.warnings.push_back(w);
  for (const std::string& name : out.workVaries)
    out.warnings.push_back("pass '" + name +
                           "' did different work in different timed frames (its counters)");
  out.counters = renderer.counters();
  // Either technique's emulation (the shadow's, then the transparency's).
  for (const std::string& why :
       {renderer.shadow().timingEmulated(), renderer.oit().timingEmulated()})
    if (!why.empty()) out.timingEmulated += (out.timingEmulated.empty() ? "" : "; ") + why;
  if (!out.timingEmulated.empty())
    out.warnings.push_back("timing emulated, not a real cost: " + out.timingEmulated);
  // One text where the two agree (or one has no tiers), else each named.
  const auto both = [](const std::string& shadow, const std::string& oit, const char* sep) {
    return shadow.empty() || oit.empty() || shadow == oit ? (shadow.empty() ? oit : shadow)
                                                          : "shadow " + shadow + sep + "oit " + oit;
  };
  out.tier = both(renderer.shadow().tier(), renderer.oit().tier(), ", ");
  out.tierReason = both(renderer.shadow().tierReason(), renderer.oit().tierReason(), "; ");

  out.device = dev.info();
  out.scene = {req.scene,
               scene.strands.strandCount(),
               scene.strands.points.size(),
               scene.strands.segmentCount(),
               scene.mesh.triangleCount(),
               scene.bounds(),
               scene.up,
               scene.upReason,
               scene.strands.thicknessFallback ? "fallback" : "strands",
               scene.groom.guideCount,
               scene.groom.instanceCount()};
  out.shadow = v.shadow.str();
  out.oit = v.oit.str();
  out.shading = v.settings.shading.spec;
  out.primitive = req.primitive;
  out.geometry = req.geometry;
  out.width = v.settings.width;
  out.height = v.settings.height;
  out.repeat = req.repeat;
  out.warmup = req.warmup;
  out.graph = renderer.graphPasses(p.timed);
  out.eyeComplexity = renderer.oit().depthComplexity();
  out.lightComplexity = renderer.shadow().depthComplexity();
}

// 6. Measures: untimed frames for what the timed ones did not make, the exact
// reference (cached per sweep) and the errors against it, then every measure unit
// (harness/measures/: own error, error by eye layers, level of detail, animation, probe,
// lights, invariants), each adding its slice.
void measures(const RenderRequest& req, const Validated& v, Plan& p, Device& dev,
              RenderProgress& progress, RenderCache* cache, RenderResult& out) {
  Renderer& renderer = *p.renderer;
  const Scene& scene = *v.scene;
  Outputs measured;
  if (req.reference && req.image)
    measured.insert(Output::Visibility);  // else the timed frames made it
  if (req.probe) measured.insert(Output::Probe);
  if (!measured.empty()) {
    out.measurementGraph = renderer.graphPasses(measured);
    progress.phase("measurement frame", p.layers);
    renderer.renderFrame(measured);
  }
  const Spec refShadow = referenceShadowSpec(v.shadow);
  // The exact reference of `drawn`, cached per sweep under `key`.
  RenderCache::Reference fresh, freshFull;
  auto exact = [&](const Scene& drawn, const std::string& key, RenderCache::Reference& mine,
                   const std::string& phase) -> const RenderCache::Reference* {
    if (cache && cache->references.count(key)) return &cache->references.at(key);
    progress.phase(phase);
    mine = renderReference(dev, drawn, v.settings, refShadow, req);
    if (!cache) return &mine;
    ++cache->referenceRenders;
    return &(cache->references[key] = std::move(mine));
  };
  // The full model's key is the scene's without its level of detail, so a run with
  // lod off and the full model's reference of a run with it on share one.
  RenderRequest fullReq = req;
  Spec fullSpec = Spec::parse(req.scene);
  fullSpec.options.erase("lod");
  fullSpec.options.erase("lod_pixels");
  fullReq.scene = fullSpec.str();
  const bool lod = v.scene != v.full;
  const RenderCache::Reference* ref = nullptr;
  if (req.reference || req.probe) {
    ref =
        exact(scene, referenceKey(lod ? req : fullReq, v.settings, refShadow), fresh, "reference");
    for (const auto& w : ref->warnings) out.warnings.push_back(w);
    if (!out.eyeComplexity) out.eyeComplexity = ref->eye;
    if (!out.lightComplexity) out.lightComplexity = ref->light;
    out.reference = {refShadow.str(), kReferenceOit};
  }
  if (req.reference) {
    if (req.image) {
      out.referenceImage = ref->image;
      out.imageError = compareImages(out.image, out.referenceImage);
      // The image as its PNG shows it: display values (imaging/flip.h).
      out.flip = computeFlip(out.image, out.referenceImage);
    }
    out.visibility = renderer.readVisibility();
    out.visibilityError = visibilityError(out.visibility, ref->visibility);
    if (req.image) {
      if (!req.references.empty()) progress.phase("further references");
      out.moreReferences = moreReferences(req, scene, v.settings, refShadow, out, cache);
      for (const auto& m : out.moreReferences)
        for (const std::string& w : m.warnings) out.warnings.push_back(w);
    }
  }
  const MeasureInputs in{req,
                         scene,
                         *v.full,
                         v.settings,
                         v.shadow,
                         v.oit,
                         refShadow,
                         v.probeDepths,
                         renderer,
                         dev,
                         cache,
                         ref,
                         [&] {
                           return exact(*v.full, referenceKey(fullReq, v.settings, refShadow),
                                        freshFull, "the full model's reference");
                         },
                         out};
  for (const MeasureDescriptor* m : measureCatalog())
    if (auto slice = m->measure(in)) out.measured.push_back(std::move(slice));
  if (req.validation) out.validationMessages = validationMessageCount();
}

}  // namespace

std::size_t RenderResult::bytesOwnedBy(Owner owner) const {
  std::size_t bytes = 0;
  for (const auto& r : resources)
    if (r.owner == owner) bytes += r.bytes;
  return bytes;
}

RenderResult runRender(const RenderRequest& req, RenderCache* cache, Device* device) {
  const Validated v = validate(req, cache);
  const RunDevice d = openDevice(req, v.settings, device);
  RenderProgress progress(*d.dev);
  RenderResult out;
  Plan p = plan(req, v, *d.dev, out);
  frames(req, p, d, progress, out);
  outputs(req, v, p, *d.dev, out);
  measures(req, v, p, *d.dev, progress, cache, out);
  return out;
}

}  // namespace sb
