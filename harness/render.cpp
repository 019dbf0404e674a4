#include "harness/render.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "backends/device.h"
#include "harness/stats.h"
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

namespace {

RenderSettings makeSettings(const RenderRequest& req, const Scene& scene) {
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

nlohmann::json boundsJson(const Bounds& b) {
  return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
}

}  // namespace

RenderOutcome runRender(const RenderRequest& req) {
  if (req.repeat < 1) throw InputError("--repeat must be at least 1");
  if (req.warmup < 0) throw InputError("--warmup must be at least 0");
  const Scene scene = makeScene(Spec::parse(req.scene));
  const Spec shadowSpec = Spec::parse(req.shadow);
  auto shadow = makeShadowTechnique(shadowSpec);
  const RenderSettings settings = makeSettings(req, scene);

  DeviceOptions dopts;
  dopts.backend = req.backend;
  dopts.platform =
      req.platform.empty() ? (req.backend == "vulkan" ? "headless" : "egl") : req.platform;
  dopts.validation = req.validation;
  if (req.backend == "vulkan" && dopts.platform != "headless")
    throw InputError("--platform " + dopts.platform +
                     " is not a Vulkan platform (valid: headless)");
  auto dev = createDevice(dopts);

  Renderer renderer(*dev, scene, settings, std::move(shadow));
  for (int i = 0; i < req.warmup; ++i) renderer.renderFrame();
  std::map<std::string, std::vector<double>> times;
  std::vector<double> totals;
  for (int i = 0; i < req.repeat; ++i) {
    double total = 0;
    for (const auto& t : renderer.renderFrame()) {
      times[t.name].push_back(t.ms);
      total += t.ms;
    }
    totals.push_back(total);
  }

  RenderOutcome out;
  out.image = imageFromRows(renderer.readColor(), static_cast<int>(settings.width),
                            static_cast<int>(settings.height), PixelType::Float32, 4);
  for (std::size_t i = 3; i < out.image.pixels.size(); i += 4) out.image.pixels[i] = 1.0f;

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
  j["primitive"] = req.primitive;
  j["size"] = {settings.width, settings.height};
  j["repeat"] = req.repeat;
  j["warmup"] = req.warmup;
  auto statsJson = [](const Stats& s) {
    return nlohmann::json{{"median", s.median},
                          {"min", s.min},
                          {"max", s.max},
                          {"mean", s.mean},
                          {"stddev", s.stddev}};
  };
  j["passes"] = nlohmann::json::array();
  for (const auto& name : renderer.passNames())
    j["passes"].push_back({{"name", name}, {"ms", statsJson(summarize(times[name]))}});
  j["frame_ms"] = statsJson(summarize(totals));

  std::map<std::string, std::size_t> byOwner;
  std::size_t total = 0;
  nlohmann::json resources = nlohmann::json::array();
  auto allocations = dev->allocations();
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
  if (req.validation) j["validation_messages"] = validationMessageCount();
  return out;
}

}  // namespace sb
