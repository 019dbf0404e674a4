#include "techniques/common/renderer.h"

#include <algorithm>

namespace sb {

namespace {
// Vulkan needs every declared binding backed; a scene without a mesh gets
// 16-byte placeholders (reported like any other buffer).
Buffer makeBuffer(Device& dev, const std::string& name, const void* data, std::size_t bytes) {
  static const uint8_t kZeros[16] = {};
  if (bytes == 0) return dev.createBuffer({name, "scene", BufferUsage::Storage, 16}, kZeros);
  return dev.createBuffer({name, "scene", BufferUsage::Storage, bytes}, data);
}
}  // namespace

Renderer::Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
                   std::unique_ptr<ShadowTechnique> shadow, std::unique_ptr<OitTechnique> oit,
                   const std::set<std::string>& outputs)
    : dev_(dev),
      settings_(settings),
      shadow_(std::move(shadow)),
      oit_(std::move(oit)),
      graph_([&dev](GraphResource r) {
        return r.texture ? dev.describe(Texture{r.id}).name : dev.describe(Buffer{r.id}).name;
      }) {
  upload(scene);
  color_ = dev.createTexture(
      {"frame.color", "frame", Format::RGBA32F, settings.width, settings.height, false});
  // --msaa N: the mesh and the hair render into N-sample colour and depth,
  // resolved into frame.color by the technique's last pass; techniques whose
  // per-pixel data is not multisampled are refused (InputError, before any work).
  const uint32_t n = settings.msaa;
  if (n > 1 && !oit_->multisampled())
    throw InputError("--msaa " + std::to_string(n) + ": transparency technique '" + oit_->name() +
                     "' keeps per-pixel data (fragment lists, layers, accumulation or occupancy "
                     "targets) that is not multisampled; it runs with --msaa 1 (multisampled: "
                     "none, wsum, wavg, wboit; stochastic transparency has its own samples= "
                     "option)");
  Texture renderColor = color_, resolved;
  if (n > 1) {
    renderColor = dev.createTexture(
        {"frame.color_ms", "frame", Format::RGBA32F, settings.width, settings.height, false, 1, n});
    resolved = color_;
  }
  depth_ = dev.createTexture({n > 1 ? "frame.depth_ms" : "frame.depth", "frame", Format::Depth32F,
                              settings.width, settings.height, false, 1, n});
  shadow_->setup(dev, gpu_, settings_);
  shading_.setup(dev, gpu_, settings_, *shadow_, renderColor, depth_);
  oit_->setup(dev, gpu_, settings_, shading_,
              {renderColor, depth_, shading_.drawsMesh(), resolved});
  wantVisibility_ = outputs.count("visibility") > 0;
  if (wantVisibility_) visibility_.setup(dev, gpu_, settings_, shading_);
  wantProbe_ = outputs.count("probe") > 0;
  if (wantProbe_) {
    if (settings_.probePoints.empty()) throw InputError("probe output without probe points");
    probe_.setup(dev, settings_.probePoints, shading_);
  }

  shadow_->prepare(dev);
  shadow_->addPasses(graph_, dev);
  shading_.addMeshPass(graph_, dev);
  if (oit_->needsPrepare()) {
    // The transparency technique sizes itself against the opaque depth.
    if (shading_.drawsMesh()) {
      const auto opaque = graph_.compile({GraphResource::of(depth_)});
      dev.beginFrame();
      for (const auto* p : opaque) p->execute();
      dev.endFrame();
    }
    oit_->prepare(dev);
  }
  oit_->addPasses(graph_, dev);
  if (wantVisibility_) visibility_.addPasses(graph_, dev);
  if (wantProbe_) probe_.addPasses(graph_, dev);
  passes_ = graph_.compile(resources(outputs));
}

std::vector<GraphResource> Renderer::resources(const std::set<std::string>& outputs) const {
  std::vector<GraphResource> r;
  for (const auto& o : outputs) {
    if (o == "color")
      r.push_back(GraphResource::of(color_));
    else if (o == "visibility" && wantVisibility_)
      r.push_back(GraphResource::of(visibility_.image()));
    else if (o == "probe" && wantProbe_)
      r.push_back(GraphResource::of(probe_.values()));
    else
      throw DeviceError("renderer: output '" + o + "' was not set up");
  }
  return r;
}

void Renderer::upload(const Scene& scene) {
  const Strands& st = scene.strands;
  std::vector<glm::vec4> points(st.points.size()), colors(st.points.size());
  for (std::size_t i = 0; i < st.points.size(); ++i) {
    const float thickness = i < st.thickness.size() ? st.thickness[i] : 0.0f;
    const float transparency = i < st.transparency.size() ? st.transparency[i] : 0.0f;
    const glm::vec3 c = i < st.colors.size() ? st.colors[i] : scene.hairColor;
    points[i] = glm::vec4(st.points[i], thickness);
    colors[i] = glm::vec4(c, scene.hairAlpha * (1.0f - transparency));
  }
  std::vector<uint32_t> segments;
  segments.reserve(st.segmentCount());
  for (std::size_t s = 0; s < st.strandCount(); ++s)
    for (uint32_t k = 0; k + 1 < st.pointCount[s]; ++k) segments.push_back(st.firstPoint[s] + k);

  const Mesh& m = scene.mesh;
  std::vector<glm::vec4> positions(m.positions.size()), normals(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    positions[i] = glm::vec4(m.positions[i], 1.0f);
    normals[i] = glm::vec4(i < m.normals.size() ? m.normals[i] : glm::vec3(0, 1, 0), 0.0f);
  }

  gpu_.points = makeBuffer(dev_, "scene.points", points.data(), points.size() * sizeof(glm::vec4));
  gpu_.colors = makeBuffer(dev_, "scene.colors", colors.data(), colors.size() * sizeof(glm::vec4));
  gpu_.segments =
      makeBuffer(dev_, "scene.segments", segments.data(), segments.size() * sizeof(uint32_t));
  gpu_.segmentCount = static_cast<uint32_t>(segments.size());
  gpu_.meshPositions = makeBuffer(dev_, "scene.mesh_positions", positions.data(),
                                  positions.size() * sizeof(glm::vec4));
  gpu_.meshNormals =
      makeBuffer(dev_, "scene.mesh_normals", normals.data(), normals.size() * sizeof(glm::vec4));
  gpu_.meshIndices =
      makeBuffer(dev_, "scene.mesh_indices", m.indices.data(), m.indices.size() * sizeof(uint32_t));
  gpu_.meshTriangles = static_cast<uint32_t>(m.triangleCount());
  gpu_.hairAlpha = scene.hairAlpha;
  gpu_.shadowAlpha = scene.shadowAlpha;
  gpu_.bounds = scene.bounds();
}

std::vector<std::string> Renderer::graphPasses() const {
  std::vector<std::string> names;
  for (const auto* p : passes_) names.push_back(p->name);
  return names;
}

std::vector<std::string> Renderer::graphPasses(const std::set<std::string>& outputs) const {
  std::vector<std::string> names;
  for (const auto* p : graph_.compile(resources(outputs))) names.push_back(p->name);
  return names;
}

std::set<uint32_t> Renderer::graphResources(const std::set<std::string>& outputs) const {
  std::set<uint32_t> ids;
  for (const auto* p : graph_.compile(resources(outputs))) {
    for (const auto& r : p->reads) ids.insert(r.id);
    for (const auto& r : p->writes) ids.insert(r.id);
  }
  return ids;
}

std::vector<PassTime> Renderer::renderFrame() { return run(passes_); }

std::vector<PassTime> Renderer::renderFrame(const std::set<std::string>& outputs) {
  return run(graph_.compile(resources(outputs)));
}

std::vector<PassTime> Renderer::run(const std::vector<const PassNode*>& passes) {
  dev_.beginFrame();
  for (const auto* p : passes) p->execute();
  dev_.endFrame();
  std::vector<PassTime> out;
  for (const auto& t : dev_.lastFrameTimings()) {
    auto it =
        std::find_if(out.begin(), out.end(), [&](const PassTime& x) { return x.name == t.name; });
    if (it == out.end()) it = out.insert(out.end(), {t.name, 0.0, 0});
    it->ms += t.ms;
    ++it->executions;
  }
  return out;
}

std::vector<uint8_t> Renderer::readColor() { return dev_.readTexture(color_); }

std::vector<uint8_t> Renderer::readVisibility() {
  if (!wantVisibility_) throw DeviceError("visibility output was not requested");
  return dev_.readTexture(visibility_.image());
}

std::vector<float> Renderer::readProbe() {
  if (!wantProbe_) throw DeviceError("probe output was not requested");
  return probe_.read(dev_);
}

std::vector<std::string> Renderer::warnings() {
  auto w = shadow_->warnings(dev_);
  for (auto& x : oit_->warnings(dev_)) w.push_back(x);
  return w;
}

}  // namespace sb
