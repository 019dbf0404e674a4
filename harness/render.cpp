#include "harness/render.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "backends/device.h"
#include "harness/invariants.h"
#include "harness/metrics.h"
#include "reports/stats.h"
#include "techniques/common/renderer.h"

namespace sb {

std::pair<uint32_t, uint32_t> parseSize(const std::string& text) {
  unsigned long w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !in.eof() ||
      text.find('-') != std::string::npos)
    throw InputError("--size " + text + ": expected WIDTHxHEIGHT, e.g. 512x512");
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw InputError("--size " + text + ": width and height must be in 1..16384");
  return {static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
}

glm::vec3 parseVec3(const std::string& text, const std::string& option) {
  glm::vec3 v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() ||
      !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw InputError(option + " " + text + ": expected three finite numbers x,y,z");
  return v;
}

RenderSettings makeRenderSettings(const RenderRequest& req, const Scene& scene) {
  RenderSettings s;
  s.width = req.width;
  s.height = req.height;
  if (req.primitive == "lines")
    s.primitive = Primitive::Lines;
  else if (req.primitive == "ribbons")
    s.primitive = Primitive::Ribbons;
  else
    throw InputError("--primitive " + req.primitive + ": expected lines or ribbons");
  if (!(req.ribbonWidth > 0.0f && req.ribbonWidth <= 64.0f))
    throw InputError("--ribbon-width must be in (0, 64] pixels");
  s.ribbonWidth = req.ribbonWidth;

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
  if (!(s.camera.fovYDegrees > 0 && s.camera.fovYDegrees < 180))
    throw InputError("--fov must be in (0, 180) degrees");
  if (!(s.camera.nearPlane > 0 && s.camera.farPlane > s.camera.nearPlane))
    throw InputError("camera planes need 0 < near < far");
  if (glm::length(s.camera.target - s.camera.eye) <= 0)
    throw InputError("camera eye and target coincide");

  LightType type = LightType::Directional;
  if (o.lightType) {
    if (*o.lightType == "point")
      type = LightType::Point;
    else if (*o.lightType != "directional")
      throw InputError("--light " + *o.lightType + ": expected directional or point");
  }
  s.light = fitLight(b, type);
  if (o.lightDirection) {
    if (glm::length(*o.lightDirection) <= 0) throw InputError("--light-direction must be non-zero");
    s.light.direction = glm::normalize(*o.lightDirection);
    if (type == LightType::Directional)
      s.light.position = b.center() - s.light.direction * (2.0f * b.radius() + 1e-6f);
  }
  if (o.lightPosition) {
    s.light.position = *o.lightPosition;
    if (!o.lightDirection && glm::length(b.center() - s.light.position) > 0)
      s.light.direction = glm::normalize(b.center() - s.light.position);
  }
  if (o.lightDirection || o.lightPosition) fitLightFrustum(s.light, b);
  if (o.lightColor) s.light.color = *o.lightColor;
  if (o.lightIntensity) s.light.intensity = *o.lightIntensity;
  return s;
}

namespace {

nlohmann::json boundsJson(const Bounds& b) {
  return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
}

nlohmann::json visibilityError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  auto floats = [](const std::vector<uint8_t>& bytes) {
    std::vector<float> v(bytes.size() / sizeof(float));
    std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
    return v;
  };
  const VisibilityError e = compareVisibility(floats(a), floats(b));
  return {{"rmse", e.rmse}, {"max", e.max}, {"pixels", e.pixels}};
}

nlohmann::json complexityJson(const std::optional<DepthComplexity>& c) {
  if (!c) return nullptr;
  return {{"max", c->max}, {"mean", c->mean}, {"fragments", c->total}};
}

Image colorImage(Renderer& r, const RenderSettings& s) {
  Image img = imageFromRows(r.readColor(), static_cast<int>(s.width), static_cast<int>(s.height),
                            PixelType::Float32, 4);
  for (std::size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
  return img;
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
  DeviceOptions dopts;
  dopts.backend = req.backend;
  dopts.platform =
      req.platform.empty() ? (req.backend == "vulkan" ? "headless" : "egl") : req.platform;
  dopts.validation = req.validation;
  if (req.backend == "vulkan" && dopts.platform != "headless")
    throw InputError("--platform " + dopts.platform +
                     " is not a Vulkan platform (valid: headless)");
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

void checkProbe(const ProbeSpec& p) {
  if (p.samples < 2 || p.samples > 1000000) throw InputError("probe samples must be in 2..1000000");
  if (p.mapSize < 1 || p.texel.x >= p.mapSize || p.texel.y >= p.mapSize)
    throw InputError("probe texel " + std::to_string(p.texel.x) + "," + std::to_string(p.texel.y) +
                     " is outside the " + std::to_string(p.mapSize) + "x" +
                     std::to_string(p.mapSize) + " map");
}

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
  k << s.light.intensity << "|" << req.image;
  if (req.probe)
    k << "|probe " << req.probe->texel.x << "," << req.probe->texel.y << "," << req.probe->mapSize
      << "," << req.probe->samples;
  return k.str();
}

RenderCache::Reference renderReference(Device& dev, const Scene& scene,
                                       const RenderSettings& settings, const Spec& refShadow,
                                       const RenderRequest& req) {
  std::set<std::string> outputs = {"visibility"};
  if (req.image) outputs.insert("color");
  if (req.probe) outputs.insert("probe");
  Renderer ref(dev, scene, settings, makeShadowTechnique(refShadow),
               makeOitTechnique(Spec::parse(kReferenceOit)), outputs);
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

}  // namespace

RenderOutcome runRender(const RenderRequest& req, RenderCache* cache) {
  if (req.repeat < 1) throw InputError("--repeat must be at least 1");
  if (req.warmup < 0) throw InputError("--warmup must be at least 0");
  if (!req.image && !req.reference)
    throw InputError("--no-image measures the visibility error only: it needs --reference");
  if (req.probe) checkProbe(*req.probe);
  if (req.invariants && !req.reference)
    throw InputError("invariants are checked against the reference: they need reference");
  const std::shared_ptr<const Scene> scenePtr = sceneFor(req.scene, cache);
  const Scene& scene = *scenePtr;
  const Spec shadowSpec = Spec::parse(req.shadow);
  const Spec oitSpec = Spec::parse(req.oit);
  auto shadow = makeShadowTechnique(shadowSpec);
  auto oit = makeOitTechnique(oitSpec);
  RenderSettings settings = makeRenderSettings(req, scene);
  std::vector<float> probeDepths;
  if (req.probe) settings.probePoints = probeRay(settings.light, *req.probe, probeDepths);

  auto dev = makeRequestDevice(req);

  // The timed frames produce what the run is for: the shaded image, or (for a
  // visibility-only run) the visibility image. Error measurements run after
  // them in untimed frames.
  const std::set<std::string> timed = {req.image ? "color" : "visibility"};
  std::set<std::string> outputs = timed;
  if (req.reference) outputs.insert("visibility");
  if (req.probe) outputs.insert("probe");
  Renderer renderer(*dev, scene, settings, std::move(shadow), std::move(oit), outputs);
  for (int i = 0; i < req.warmup; ++i) renderer.renderFrame(timed);
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> times;
  std::map<std::string, int> executions;
  std::vector<double> totals;
  for (int i = 0; i < req.repeat; ++i) {
    double total = 0;
    for (const auto& t : renderer.renderFrame(timed)) {
      if (!times.count(t.name)) order.push_back(t.name);
      times[t.name].push_back(t.ms);
      executions[t.name] = t.executions;
      total += t.ms;
    }
    totals.push_back(total);
  }

  RenderOutcome out;
  if (req.image) out.image = colorImage(renderer, settings);
  // Memory of this run's techniques only (before any reference is built).
  auto allocations = dev->allocations();
  std::vector<std::string> warnings = scene.warnings;  // the input's, then the techniques'
  for (const auto& w : renderer.warnings()) warnings.push_back(w);

  const DeviceInfo info = dev->info();
  nlohmann::json& j = out.report;
  j["backend"] = info.backend;
  j["platform"] = info.platform;
  j["device"] = info.device;
  j["driver"] = info.driver;
  j["timing"] = info.timing;
  j["lines"] = info.lines;
  j["scene"] = {{"spec", req.scene},
                {"strands", scene.strands.strandCount()},
                {"points", scene.strands.points.size()},
                {"segments", scene.strands.segmentCount()},
                {"mesh_triangles", scene.mesh.triangleCount()},
                {"bounds", boundsJson(scene.bounds())}};
  j["shadow"] = shadowSpec.str();
  j["oit"] = oitSpec.str();
  j["primitive"] = req.primitive;
  j["size"] = {settings.width, settings.height};
  j["repeat"] = req.repeat;
  j["warmup"] = req.warmup;
  j["graph"] = renderer.graphPasses(timed);
  j["passes"] = nlohmann::json::array();
  for (const auto& name : order)
    j["passes"].push_back(
        {{"name", name}, {"executions", executions[name]}, {"ms", statsJson(times[name])}});
  j["frame_ms"] = statsJson(totals);

  std::map<std::string, std::size_t> byOwner;
  std::size_t total = 0;
  nlohmann::json resources = nlohmann::json::array();
  std::sort(allocations.begin(), allocations.end(),
            [](const ResourceBytes& a, const ResourceBytes& b) { return a.name < b.name; });
  for (const auto& r : allocations) {
    resources.push_back({{"name", r.name}, {"owner", r.owner}, {"bytes", r.bytes}});
    byOwner[r.owner] += r.bytes;
    total += r.bytes;
  }
  j["memory"] = {{"shadow_bytes", byOwner["shadow"]},
                 {"oit_bytes", byOwner["oit"]},
                 {"scene_bytes", byOwner["scene"]},
                 {"frame_bytes", byOwner["frame"]},
                 {"total_bytes", total},
                 {"resources", resources}};

  std::optional<DepthComplexity> eye = renderer.oit().depthComplexity();
  std::optional<DepthComplexity> light = renderer.shadow().depthComplexity();
  std::set<std::string> measured;
  if (req.reference && req.image) measured.insert("visibility");  // else the timed frames made it
  if (req.probe) measured.insert("probe");
  if (!measured.empty()) {
    j["measurement_graph"] = renderer.graphPasses(measured);
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
      fresh = renderReference(*dev, scene, settings, refShadow, req);
      if (cache) {
        ++cache->referenceRenders;
        ref = &(cache->references[key] = std::move(fresh));
      } else {
        ref = &fresh;
      }
    }
    for (const auto& w : ref->warnings) warnings.push_back(w);
    if (!eye) eye = ref->eye;
    if (!light) light = ref->light;
    j["reference"] = {{"shadow", refShadow.str()}, {"oit", kReferenceOit}};
    if (req.reference) {
      nlohmann::json error;
      if (req.image) {
        out.reference = ref->image;
        error["image"] = toJson(compareImages(out.image, out.reference));
      }
      out.visibility = renderer.readVisibility();
      error["visibility"] = visibilityError(out.visibility, ref->visibility);
      j["error"] = error;
    }
    if (req.probe) {
      out.probe = renderer.readProbe();
      j["probe"] = {{"texel", {req.probe->texel.x, req.probe->texel.y}},
                    {"map_size", req.probe->mapSize},
                    {"light_depth", probeDepths},
                    {"exact", ref->probe},
                    {"visibility", out.probe}};
    }
    if (req.invariants) {
      std::vector<InvariantFailure> failures;
      if (req.image) {
        const std::string last = j["graph"].empty() ? "" : j["graph"].back().get<std::string>();
        checkColor(out.image, KajiyaKayShading::maxRadiance(settings), last, failures);
      }
      if (req.reference) {
        checkVisibility(out.visibility, "visibility", failures);
        for (const auto& [kind, e] : j["error"].items())
          for (const auto& [metric, v] : e.items())
            // PSNR is infinite (null) exactly when the images are identical.
            if ((v.is_null() && !(metric == "psnr" && e.value("identical", false))) ||
                (v.is_number_float() && !std::isfinite(v.get<double>())))
              failures.push_back(
                  {"reference", "error " + kind + "." + metric + " is not a number"});
      }
      if (req.probe) {
        checkRay(out.probe, "probe (" + shadowSpec.name + ")", failures);
        checkRay(ref->probe, "probe (reference)", failures);
      }
      for (Texture t : renderer.shadow().lookupTextures()) {
        const TextureDesc d = dev->describe(t);
        checkMap(dev->readTexture(t), d.format, "map " + d.name, failures);
      }
      nlohmann::json list = nlohmann::json::array();
      for (const auto& f : failures) list.push_back({{"pass", f.pass}, {"what", f.what}});
      j["invariants"] = {{"failures", list}};
    }
  }
  if (eye || light)
    j["depth_complexity"] = {{"eye", complexityJson(eye)}, {"light", complexityJson(light)}};
  j["warnings"] = warnings;
  if (req.validation) j["validation_messages"] = validationMessageCount();
  return out;
}

}  // namespace sb
