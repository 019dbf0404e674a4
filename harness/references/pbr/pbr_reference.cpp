#include "harness/references/pbr/pbr_reference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/fnv.h"
#include "harness/render_steps.h"
#include "harness/setting_values.h"
#include "harness/stop.h"
#include "render/common/unit.h"
#include "render/shading/hair_shading.h"
#include "reports/files.h"

namespace sb {

namespace fs = std::filesystem;

namespace {

// Bumped when the pbr code changes what it renders: every cached image is then stale (2: the
// tracer drops Embree's end caps and near-origin misses, shadow rays start at texel centres;
// 3: h's sign, stratified pixel samples, the noise target on the RMS standard error).
constexpr const char* kPbrCodeVersion = "pbr-3";
constexpr const char* kCacheMagic = "strandbench pbr reference 1\n";

float strandWidthPixels(const RenderSettings& s) {
  return s.primitive == Primitive::Lines ? 1.0f : s.ribbonWidth;
}

glm::mat4 cameraViewProj(const RenderSettings& s) {
  return s.camera.projection(float(s.width) / float(s.height)) * s.camera.view();
}

std::vector<Light> allLights(const RenderSettings& s) {
  std::vector<Light> l{s.light};
  l.insert(l.end(), s.extraLights.begin(), s.extraLights.end());
  return l;
}

template <class T>
uint64_t fnvVector(uint64_t h, const std::vector<T>& v) {
  return fnv1a(h, v.data(), v.size() * sizeof(T));
}

// The exact shadow's map (refShadow is always the exact reference's shadow).
long long mapSize(const Spec& refShadow) { return referenceLightMap(refShadow).size; }
double mapBias(const Spec& refShadow) { return referenceLightMap(refShadow).bias; }

// Everything the reference's pixels depend on, as text (hashed into the cache's key).
std::string cacheKeyText(const Scene& scene, const RenderSettings& s, const Spec& refShadow,
                         const PbrReference& spec) {
  std::ostringstream k;
  k.precision(9);
  auto v3 = [&](const glm::vec3& v) { k << v.x << "," << v.y << "," << v.z << ";"; };
  k << kPbrCodeVersion << "|" << spec.str() << "|" << scene.name << "|";
  uint64_t h = kFnvOffset;
  const Strands& st = scene.strands;
  h = fnvVector(h, st.firstPoint);
  h = fnvVector(h, st.pointCount);
  h = fnvVector(h, st.points);
  h = fnvVector(h, st.colors);
  // A fallback thickness is not drawn (the world width takes the reference's own).
  if (!st.thicknessFallback) h = fnvVector(h, st.thickness);
  h = fnvVector(h, st.transparency);
  h = fnvVector(h, scene.mesh.positions);
  h = fnvVector(h, scene.mesh.normals);
  h = fnvVector(h, scene.mesh.indices);
  k << std::hex << h << std::dec << "|" << scene.hairAlpha << "," << s.shading.shadowAlpha(scene)
    << ";";
  v3(scene.hairColor);
  k << s.width << "x" << s.height << "|" << int(s.primitive) << "," << s.ribbonWidth << "|";
  v3(s.camera.eye);
  v3(s.camera.target);
  v3(s.camera.up);
  k << s.camera.fovYDegrees << "," << s.camera.nearPlane << "," << s.camera.farPlane << "|";
  for (const Light& l : allLights(s)) {
    k << int(l.type) << ";";
    v3(l.position);
    v3(l.direction);
    v3(l.color);
    k << l.intensity << "," << l.nearPlane << "," << l.farPlane << "," << l.orthoHalfExtent << ","
      << l.fovYDegrees << "|";
  }
  v3(s.background);
  k << s.ambient << "|";
  // The exact shadow's map (size, bias) counts in transmittance mode and for footprint widths.
  if (spec.mode == "transmittance" || pbrWidthModel(spec) == "footprint")
    k << refShadow.str() << "|";
  // The shading model counts in transmittance mode only (the path's is the hair BSDF).
  if (spec.mode == "transmittance") {
    k << s.shading.spec << ";" << s.shading.ambient << ";" << std::hex;
    for (const std::byte b : s.shading.params) k << int(b) << ",";  // the model's own block
    k << std::dec;
  }
  return k.str();
}

// The cached image: the magic line, the key text's length and text, the header numbers, then
// the mean (RGB floats) and the standard error per pixel.
struct CacheHeader {
  uint32_t width, height, spp, stoppedAtTarget;
  double renderMs;
};

std::string cacheBytes(const std::string& key, const pbr::RenderImage& img, double renderMs) {
  std::string out = kCacheMagic;
  const uint64_t n = key.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out += key;
  const CacheHeader h{img.width, img.height, img.spp, img.stoppedAtTarget ? 1u : 0u, renderMs};
  out.append(reinterpret_cast<const char*>(&h), sizeof h);
  out.append(reinterpret_cast<const char*>(img.mean.data()), img.mean.size() * sizeof(glm::vec3));
  out.append(reinterpret_cast<const char*>(img.stderror.data()),
             img.stderror.size() * sizeof(float));
  return out;
}

// The cached image when the file holds exactly this key (a hash collision or a damaged file
// reads as a miss).
bool readCache(const fs::path& file, const std::string& key, pbr::RenderImage& img,
               double& renderMs) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t at = std::strlen(kCacheMagic);
  if (bytes.compare(0, at, kCacheMagic) != 0 || bytes.size() < at + sizeof(uint64_t)) return false;
  uint64_t n = 0;
  std::memcpy(&n, bytes.data() + at, sizeof n);
  at += sizeof n;
  if (n != key.size() || bytes.compare(at, n, key) != 0) return false;
  at += n;
  CacheHeader h{};
  if (bytes.size() < at + sizeof h) return false;
  std::memcpy(&h, bytes.data() + at, sizeof h);
  at += sizeof h;
  const std::size_t pixels = std::size_t(h.width) * h.height;
  if (bytes.size() != at + pixels * (sizeof(glm::vec3) + sizeof(float))) return false;
  img.width = h.width;
  img.height = h.height;
  img.spp = h.spp;
  img.stoppedAtTarget = h.stoppedAtTarget != 0;
  img.mean.resize(pixels);
  img.stderror.resize(pixels);
  std::memcpy(img.mean.data(), bytes.data() + at, pixels * sizeof(glm::vec3));
  std::memcpy(img.stderror.data(), bytes.data() + at + pixels * sizeof(glm::vec3),
              pixels * sizeof(float));
  renderMs = h.renderMs;
  return true;
}

// The scene's shading model on the CPU: the hair passes' shadeHair and the mesh pass
// (render/shading/hair_shading.glsl, mesh.frag), every light's term weighted by its
// visibility, the ambient term once.
pbr::ShadeFn shadingOf(const RenderSettings& s) {
  const std::vector<Light> lights = allLights(s);
  return [s, lights](const pbr::SurfacePoint& p, const std::vector<float>& vis) {
    const ShadingModel& m = s.shading;
    const float ambient = s.ambient ? 1.0f : 0.0f;
    const glm::vec3 V = glm::normalize(s.camera.eye - p.position);
    glm::vec3 out(0.0f);
    if (p.mesh) {
      glm::vec3 N = p.direction;
      if (glm::dot(N, V) < 0) N = -N;
      const glm::vec3 albedo(HairShading::kMeshMaterial);
      out = albedo * HairShading::kMeshMaterial.w * ambient;
      for (std::size_t l = 0; l < lights.size(); ++l) {
        const Light& L = lights[l];
        const glm::vec3 toL = L.type == LightType::Point ? glm::normalize(L.position - p.position)
                                                         : -glm::normalize(L.direction);
        out += albedo * vis[l] * std::max(glm::dot(N, toL), 0.0f) * L.color * L.intensity;
      }
      return out;
    }
    const glm::vec3 T = glm::normalize(p.direction), c = p.color;
    out = m.ambient * ambient * c;
    for (std::size_t l = 0; l < lights.size(); ++l) {
      const Light& Lt = lights[l];
      const glm::vec3 L = Lt.type == LightType::Point ? glm::normalize(Lt.position - p.position)
                                                      : -glm::normalize(Lt.direction);
      const glm::vec3 direct = m.direct(T, L, V, c);
      out += vis[l] * direct * Lt.color * Lt.intensity;
    }
    return out;
  };
}

}  // namespace

std::string pbrCacheDir() {
  if (const char* d = std::getenv("SB_PBR_CACHE"); d && *d)
    return std::string(d) == "off" ? "" : std::string(d);
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    return (fs::path(x) / "strandbench" / "pbr").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "strandbench" / "pbr").string();
  return "";
}

std::string pbrWidthModel(const PbrReference& spec) {
  if (spec.width != "auto") return spec.width;
  return spec.mode == "transmittance" ? "footprint" : "world";
}

double pbrThickness(const Scene& scene, const RenderSettings& s, const PbrReference& spec) {
  return spec.thickness > 0 ? spec.thickness : pixelAtSceneCentre(scene, s);
}

// footprint: shadow rays start at the centres of the exact shadow's texels (transmittance mode
// with the raster's widths: the same lookup as the raster's).
pbr::StrandScene pbrScene(const Scene& scene, const RenderSettings& s, const Spec& refShadow,
                          bool footprint) {
  pbr::StrandScene out;
  const Strands& st = scene.strands;
  out.colors.resize(st.points.size());
  out.alpha.resize(st.points.size());
  for (std::size_t i = 0; i < st.points.size(); ++i) {
    out.colors[i] = i < st.colors.size() ? st.colors[i] : scene.hairColor;
    const float transparency = i < st.transparency.size() ? st.transparency[i] : 0.0f;
    out.alpha[i] = scene.hairAlpha * (1.0f - transparency);
    // As the renderer uploads it (render/frame/renderer.cpp): the fibre's opacity instead.
    if (s.shading.fibreShadowAlpha) out.alpha[i] = s.shading.fibreShadowAlpha(out.colors[i]);
  }
  out.meshNormals = scene.mesh.normals;
  out.shadowAlpha = s.shading.shadowAlpha(scene);
  out.background = s.background;
  out.meshAlbedo = glm::vec3(HairShading::kMeshMaterial);
  const float bias = static_cast<float>(mapBias(refShadow));
  for (const Light& l : allLights(s)) {
    pbr::TraceLight t;
    t.point = l.type == LightType::Point;
    t.position = l.position;
    t.toLight = -glm::normalize(l.direction);
    t.color = l.color * l.intensity;
    t.viewProj = l.projection() * l.view();
    t.bias = bias;
    t.invViewProj = glm::inverse(t.viewProj);
    if (footprint) t.texels = static_cast<uint32_t>(mapSize(refShadow));
    out.lights.push_back(t);
  }
  out.eye = s.camera.eye;
  out.invViewProj = glm::inverse(cameraViewProj(s));
  out.width = s.width;
  out.height = s.height;
  return out;
}

pbr::TraceGeometry pbrGeometry(const Scene& scene, const RenderSettings& s, const Spec& refShadow,
                               const PbrReference& spec, int light) {
  pbr::TraceGeometry g;
  const Strands& st = scene.strands;
  g.firstPoint = st.firstPoint;
  g.pointCount = st.pointCount;
  g.points = st.points;
  g.meshPositions = scene.mesh.positions;
  g.meshIndices = scene.mesh.indices;
  g.radius.resize(st.points.size());
  const float px = strandWidthPixels(s);
  if (pbrWidthModel(spec) == "world") {
    const float fallback = static_cast<float>(pbrThickness(scene, s, spec));
    for (std::size_t i = 0; i < st.points.size(); ++i) {
      const float t = i < st.thickness.size() && !st.thicknessFallback ? st.thickness[i] : 0.0f;
      g.radius[i] = 0.5f * (t > 0 ? t : fallback);
    }
    return g;
  }
  // Footprint: ribbon_width pixels (a line: one) wide as the eye sees it, or as many texels
  // of light l's map: the width each rasterized view draws.
  glm::mat4 proj, viewProj;
  float side;
  if (light < 0) {
    proj = s.camera.projection(float(s.width) / float(s.height));
    viewProj = proj * s.camera.view();
    side = float(s.height);
  } else {
    const Light l = allLights(s)[std::size_t(light)];  // a copy: the list is a temporary
    proj = l.projection();
    viewProj = proj * l.view();
    side = float(mapSize(refShadow));
  }
  for (std::size_t i = 0; i < st.points.size(); ++i)
    g.radius[i] = 0.5f * px * worldPixelAt(proj, viewProj, st.points[i], side);
  return g;
}

RenderResult::MoreReference PbrReference::render(const ReferenceInputs& in) const {
  const Scene& scene = in.scene;
  const RenderSettings& s = in.settings;
  const Spec& refShadow = in.refShadow;
  const PbrReference& spec = *this;
  const auto start = std::chrono::steady_clock::now();
  RenderResult::MoreReference m;
  m.name = "pbr";
  m.spec = spec.str();
  m.samples = spec.spp;
  m.width = s.width;
  m.height = s.height;
  auto slice = std::make_shared<PbrSlice>();
  PbrSlice& info = *slice;
  info.mode = spec.mode;
  info.width = pbrWidthModel(spec);
  // The tracer has no environment light: the raster's ambient term (its strength here) is
  // part of what the two differ by unless the render turns it off.
  info.rasterAmbient = s.ambient ? double(s.shading.ambient) : 0.0;
  info.shadowRays = spec.mode == "transmittance" ? "shadow_alpha per strand"
                    : spec.mode == "single"      ? "attenuated by each fibre's transmittance"
                                                 : "opaque (transmission is scattering)";
  if (info.width == "world") {
    // The strands' own widths where they have them (their mean), else the fallback; a
    // loader's stand-in for a width the file did not give is not the strands' own.
    double sum = 0;
    std::size_t own = 0;
    if (!scene.strands.thicknessFallback)
      for (float t : scene.strands.thickness)
        if (t > 0) {
          sum += t;
          ++own;
        }
    info.thicknessSource = own ? "strands" : "fallback";
    info.thickness = own ? sum / double(own) : pbrThickness(scene, s, spec);
    if (scene.strands.thicknessFallback)
      m.warnings.push_back(
          "the strand file gives no thickness: the path reference's strands are " +
          setting_values::numberText(info.thickness) + " world units wide, its fallback (" +
          (spec.thickness > 0 ? "thickness="
                              : "one pixel at the scene's centre; thickness= sets it") +
          ")");
  }
  if (info.width == "footprint") m.lightSize = static_cast<uint32_t>(mapSize(refShadow));

  const std::string key = cacheKeyText(scene, s, refShadow, spec);
  info.key = hex64(fnv1a(kFnvOffset, key.data(), key.size()));
  const std::string dir = pbrCacheDir();
  if (!dir.empty()) info.file = (fs::path(dir) / (info.key + ".pbr")).string();

  pbr::RenderImage img;
  double renderMs = 0;
  if (!info.file.empty() && readCache(info.file, key, img, renderMs)) {
    info.cacheHit = true;
  } else {
    const pbr::StrandScene ps =
        pbrScene(scene, s, refShadow, spec.mode == "transmittance" && info.width == "footprint");
    const pbr::StrandTracer eye(pbrGeometry(scene, s, refShadow, spec));
    std::vector<std::unique_ptr<pbr::StrandTracer>> own;
    std::vector<const pbr::StrandTracer*> lights{&eye};
    if (spec.mode == "transmittance" && info.width == "footprint") {
      lights.clear();
      for (std::size_t l = 0; l < ps.lights.size(); ++l) {
        own.push_back(std::make_unique<pbr::StrandTracer>(
            pbrGeometry(scene, s, refShadow, spec, static_cast<int>(l))));
        lights.push_back(own.back().get());
      }
    }
    pbr::RenderOptions o;
    o.mode = spec.mode == "path"     ? pbr::Mode::Path
             : spec.mode == "single" ? pbr::Mode::Single
                                     : pbr::Mode::Transmittance;
    o.spp = static_cast<uint32_t>(spec.spp);
    o.bounces = static_cast<uint32_t>(spec.bounces);
    o.noiseTarget = static_cast<float>(spec.noise);
    o.seed = static_cast<uint64_t>(spec.seed);
    ProgressLine line("pbr reference " + spec.mode + " " + std::to_string(s.width) + "x" +
                      std::to_string(s.height));
    const auto t0 = std::chrono::steady_clock::now();
    img = pbr::renderStrands(ps, eye, lights, o, shadingOf(s), [&line](const std::string& text) {
      throwIfStopped();
      line.update(text);
    });
    renderMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!info.file.empty()) {
      fs::create_directories(dir);
      writeFileAtomic(info.file, cacheBytes(key, img, renderMs));
    }
  }
  info.spp = img.spp;
  info.stoppedAtTarget = img.stoppedAtTarget;
  info.meanStderr = img.meanStderr();
  info.noiseRmse = img.rmsStderr();
  info.renderMs = renderMs;
  m.referenceImage = Image(int(img.width), int(img.height), 4, 1.0f);
  for (std::size_t i = 0; i < img.mean.size(); ++i)
    for (int c = 0; c < 3; ++c) m.referenceImage.pixels[i * 4 + std::size_t(c)] = img.mean[i][c];
  m.hostBytes = img.mean.size() * (sizeof(glm::vec3) + sizeof(float) + 16);
  m.slice = std::move(slice);
  m.wallMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return m;
}

std::string PbrReference::str() const {
  // Written as before the unit (precision 9): the text is part of the disk cache's key.
  std::ostringstream o;
  o.precision(9);
  o << "pbr:mode=" << mode << ",spp=" << spp << ",bounces=" << bounces << ",width=" << width
    << ",thickness=" << thickness << ",noise=" << noise << ",seed=" << seed;
  return o.str();
}

void PbrSlice::json(const RenderResult::MoreReference& m, nlohmann::json& e) const {
  // The reference's own noise: sqrt(mean stderr^2) is the RMSE a perfect image would
  // score against it, so rmse^2 - noise^2 estimates the error without it.
  auto withoutNoise = [this](double rmse) {
    return std::sqrt(std::max(0.0, rmse * rmse - noiseRmse * noiseRmse));
  };
  e["noise"] = {{"rmse", noiseRmse},
                {"mean_stderr", meanStderr},
                {"rmse_without_noise", withoutNoise(m.image.rmse)}};
  // At the best exposure scale: the error a brightness difference does not explain.
  e["scaled"] = {{"scale", m.bestScale},
                 {"rmse", m.scaledRmse},
                 {"rmse_without_noise", withoutNoise(m.scaledRmse)}};
  e["mean"] = {{"image", m.imageMean}, {"reference", m.referenceMean}};
  e["reference"]["pbr"] = {{"mode", mode},
                           {"ambient", {{"tracer", "none"}, {"raster", rasterAmbient}}},
                           {"shadow_rays", shadowRays},
                           {"width", width},
                           {"thickness", thickness},
                           {"thickness_source", thicknessSource},
                           {"spp", spp},
                           {"stopped_at_noise_target", stoppedAtTarget},
                           {"cache", {{"key", key}, {"file", file}, {"hit", cacheHit}}},
                           {"render_ms", renderMs}};
}

const PbrReference& pbrOptions(const ReferenceSpec& spec) {
  const auto* p = dynamic_cast<const PbrReference*>(spec.unit.get());
  if (!p) throw InputError("reference '" + spec.str() + "' is not a pbr reference");
  return *p;
}

const PbrSlice* pbrSlice(const RenderResult::MoreReference& m) {
  return dynamic_cast<const PbrSlice*>(m.slice.get());
}

}  // namespace sb
