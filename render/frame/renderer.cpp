#include "render/frame/renderer.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "render/common/composite.h"
#include "render/common/unit.h"
#include "render/generation/mesh_groom.h"
#include "render/graph/frame_planner.h"

namespace sb {

namespace {
// The transparency techniques that render into multisampled targets, from the registry.
std::string multisampledNames() {
  std::string s;
  for (const std::string& name : techniqueNames(
           Family::Transparency, [](const TechniqueDescriptor& d) { return d.caps.multisampling; }))
    s += (s.empty() ? "" : ", ") + name;
  return s;
}

// Vulkan needs every declared binding backed; a scene without a mesh gets
// 16-byte placeholders (reported like any other buffer).
Buffer makeBuffer(Device& dev, const std::string& name, const void* data, std::size_t bytes) {
  static const uint8_t kZeros[16] = {};
  if (bytes == 0) return dev.createBuffer({name, Owner::Scene, BufferUsage::Storage, 16}, kZeros);
  return dev.createBuffer({name, Owner::Scene, BufferUsage::Storage, bytes}, data);
}

// Names graph resources in messages.
FrameGraph::Namer resourceNamer(Device& dev) {
  return [&dev](GraphResource r) {
    return r.texture ? dev.describe(Texture{r.id}).name : dev.describe(Buffer{r.id}).name;
  };
}

// Pipelines created in its lifetime are declared, not compiled (Device::setDeferPipelines).
class DeferredPipelines {
 public:
  explicit DeferredPipelines(Device& dev) : dev_(dev) { dev_.setDeferPipelines(true); }
  ~DeferredPipelines() { dev_.setDeferPipelines(false); }
  DeferredPipelines(const DeferredPipelines&) = delete;
  DeferredPipelines& operator=(const DeferredPipelines&) = delete;

 private:
  Device& dev_;
};

// Buffers created with data in its lifetime are made when first used
// (Device::setDeferMaking); leaving it makes nothing.
class DeferredMaking {
 public:
  explicit DeferredMaking(Device& dev) : dev_(dev) { dev_.setDeferMaking(true); }
  ~DeferredMaking() { dev_.setDeferMaking(false); }
  DeferredMaking(const DeferredMaking&) = delete;
  DeferredMaking& operator=(const DeferredMaking&) = delete;

 private:
  Device& dev_;
};

// What the memory guard is told before a technique's preparation.
std::string preparing(const std::string& family, const std::string& technique) {
  return "this run (at least: the resources made so far and those " + family + " technique '" +
         technique + "' declared, counted before its preparation)";
}
}  // namespace

Renderer::Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
                   std::unique_ptr<ShadowTechnique> shadow, std::unique_ptr<OitTechnique> oit,
                   const Outputs& outputs)
    : Renderer(dev, scene, settings, one(std::move(shadow), std::move(oit), settings), outputs) {}

Renderer::Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
                   const Spec& shadow, const Spec& oit, const Outputs& outputs)
    : Renderer(dev, scene, settings, perLight(shadow, oit, settings), outputs) {}

std::vector<Renderer::Techniques> Renderer::one(std::unique_ptr<ShadowTechnique> shadow,
                                                std::unique_ptr<OitTechnique> oit,
                                                const RenderSettings& settings) {
  if (!settings.extraLights.empty())
    throw DeviceError("renderer: " + std::to_string(settings.extraLights.size()) +
                      " extra lights need techniques per light (make the renderer from specs)");
  std::vector<Techniques> t;
  t.push_back({std::move(shadow), std::move(oit)});
  return t;
}

std::vector<Renderer::Techniques> Renderer::perLight(const Spec& shadow, const Spec& oit,
                                                     const RenderSettings& settings) {
  std::vector<Techniques> t;
  for (std::size_t i = 0; i <= settings.extraLights.size(); ++i)
    t.push_back({makeShadowTechnique(shadow), makeOitTechnique(oit)});
  return t;
}

std::string Renderer::lightPrefix(std::size_t i) {
  return i == 0 ? "" : "light" + std::to_string(i + 1) + ".";
}

Renderer::Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
                   std::vector<Techniques> techniques, const Outputs& outputs)
    : dev_(dev), group_(dev), settings_(settings), graph_(resourceNamer(dev)) {
  GroupScope owned(dev_, group_);
  // Nothing is made, the scene's buffers included, until the whole plan has
  // been put to the memory guard.
  std::optional<DeferredMaking> making(std::in_place, dev_);
  upload(scene);
  for (std::size_t i = 0; i < techniques.size(); ++i) {
    auto light = std::make_unique<LightChain>();
    light->settings = settings;
    if (i > 0) {  // its own light only: ambient light and the background count once
      light->settings.light = settings.extraLights[i - 1];
      light->settings.extraLights.clear();
      light->settings.ambient = false;
      light->settings.background = glm::vec3(0.0f);
    }
    light->shadow = std::move(techniques[i].shadow);
    light->oit = std::move(techniques[i].oit);
    lights_.push_back(std::move(light));
  }
  // --msaa N: the mesh and the hair render into N-sample colour and depth,
  // resolved into frame.color by the technique's last pass; techniques whose
  // per-pixel data is not multisampled are refused (InputError, before any work).
  const uint32_t n = settings.msaa;
  if (n > 1 && !oit().multisampled()) {
    const TechniqueDescriptor* d = tryFindTechnique(Family::Transparency, oit().name());
    const std::string reason = d && !d->caps.msaaRefusal.empty()
                                   ? d->caps.msaaRefusal
                                   : "it keeps per-pixel data that is not multisampled";
    throw InputError("--msaa " + std::to_string(n) + ": transparency technique '" + oit().name() +
                     "' does not take multisampled targets: " + reason +
                     "; it runs with --msaa 1 (multisampled: " + multisampledNames() +
                     "; a technique may have its own samples= option)");
  }
  // The visibility and probe outputs are the key light's.
  wantVisibility_ = outputs.count(Output::Visibility) > 0;
  wantProbe_ = outputs.count(Output::Probe) > 0;
  // Cull before building: every part declares its nodes first; only the
  // parts with a kept node compile their pipelines and run their preparation.
  std::set<uint32_t> sumPipelines;
  {
    DeferredPipelines deferred(dev_);
    for (std::size_t i = 0; i < lights_.size(); ++i) declareLight(*lights_[i], i);
    color_ = lights_[0]->color;
    const uint32_t first = dev_.nextHandleId();
    addSumPass();
    sumPipelines = dev_.pipelineIdsFrom(first);
  }
  passes_ = graph_.compile(resources(outputs));
  guardPlan(outputs);
  dev_.makeDeferredBuffers();
  making.reset();
  if (settings_.geometry == GeometryPath::Compute) preparations_.push_back("scene.generate");
  for (std::size_t i = 0; i < lights_.size(); ++i) buildLight(*lights_[i], i);
  if (lights_.size() > 1 &&
      kept({Unit::Kind::Measures, lights_.back()->endNode, graph_.nodes().size(), {}}))
    dev_.compilePipelines(sumPipelines);
  gpu_.hostPoints = nullptr;  // the scene is the caller's: only the setup above reads it
}

// The whole plan before anything is made: what the kept passes use and what
// the kept techniques declared (their preparations' too), lists that a counting
// pass sizes at their declared size.
void Renderer::guardPlan(const Outputs& outputs) const {
  std::set<uint32_t> ids = graphResources(outputs);
  bool counted = false;
  for (const auto& light : lights_) {
    if (kept(light->units[0])) ids.insert(light->shadowIds.begin(), light->shadowIds.end());
    if (kept(light->units[2])) {
      ids.insert(light->oitIds.begin(), light->oitIds.end());
      counted = counted || light->oit->needsPrepare();
    }
  }
  FramePlanner::of(dev_).guardMemory(
      ids, counted ? "this run (its whole plan; the fragment lists before the "
                     "counting pass that sizes them)"
                   : "this run (its whole plan)");
}

bool Renderer::kept(const Unit& unit) const {
  const PassNode* first = graph_.nodes().data();
  return std::any_of(passes_.begin(), passes_.end(), [&](const PassNode* p) {
    const auto index = static_cast<std::size_t>(p - first);
    return index >= unit.firstNode && index < unit.endNode;
  });
}

Owner Renderer::ownerOf(std::size_t node) const {
  for (const auto& light : lights_)
    for (const Unit& unit : light->units)
      if (node >= unit.firstNode && node < unit.endNode) {
        if (unit.kind == Unit::Kind::Shadow) return Owner::Shadow;
        if (unit.kind == Unit::Kind::Oit) return Owner::Oit;
        return Owner::Frame;
      }
  return Owner::Frame;  // the lights' sum
}

void Renderer::declareLight(LightChain& light, std::size_t index) {
  Device& dev = dev_;
  LabelScope scope(dev, lightPrefix(index));
  const RenderSettings& s = light.settings;
  const uint32_t n = s.msaa;
  light.color =
      dev.createTexture({"frame.color", Owner::Frame, Format::RGBA32F, s.width, s.height, false});
  Texture renderColor = light.color, resolved;
  if (n > 1) {
    renderColor = dev.createTexture(
        {"frame.color_ms", Owner::Frame, Format::RGBA32F, s.width, s.height, false, 1, n});
    resolved = light.color;
  }
  // Every light draws its mesh into the same depth, before its hair reads it.
  if (index == 0)
    depth_ = dev.createTexture({n > 1 ? "frame.depth_ms" : "frame.depth", Owner::Frame,
                                Format::Depth32F, s.width, s.height, false, 1, n});
  using Kind = Unit::Kind;
  light.units = {{Kind::Shadow}, {Kind::Shading}, {Kind::Oit}, {Kind::Measures}};
  // Each part's setup, then its passes: the pipelines each declared.
  auto declared = [&](Unit& unit, const auto& declare) {
    const uint32_t first = dev.nextHandleId();
    declare();
    for (uint32_t id : dev.pipelineIdsFrom(first)) unit.pipelines.insert(id);
    return dev.resourceIdsFrom(first);
  };
  auto addPasses = [&](Unit& unit, const auto& add) {
    unit.firstNode = graph_.nodes().size();
    declared(unit, add);
    unit.endNode = graph_.nodes().size();
  };
  const bool key = index == 0;
  light.shadowIds = declared(light.units[0], [&] { light.shadow->setup(dev, gpu_, s); });
  declared(light.units[1],
           [&] { light.shading.setup(dev, gpu_, s, *light.shadow, renderColor, depth_); });
  light.oitIds = declared(light.units[2], [&] {
    light.oit->setup(dev, gpu_, s, light.shading,
                     {renderColor, depth_, light.shading.drawsMesh(), resolved});
  });
  light.oitIds.insert(depth_.id);  // drawn before its preparation
  declared(light.units[3], [&] {
    if (key && wantVisibility_) visibility_.setup(dev, gpu_, s, light.shading);
    if (key && wantProbe_) {
      if (s.probePoints.empty()) throw InputError("probe output without probe points");
      probe_.setup(dev, s.probePoints, light.shading);
    }
  });
  addPasses(light.units[0], [&] { light.shadow->addPasses(graph_, dev); });
  addPasses(light.units[1], [&] { light.shading.addMeshPass(graph_, dev); });
  addPasses(light.units[2], [&] { light.oit->addPasses(graph_, dev); });
  addPasses(light.units[3], [&] {
    if (key && wantVisibility_) visibility_.addPasses(graph_, dev);
    if (key && wantProbe_) probe_.addPasses(graph_, dev);
  });
  light.endNode = graph_.nodes().size();
}

void Renderer::buildLight(LightChain& light, std::size_t index) {
  Device& dev = dev_;
  LabelScope scope(dev, lightPrefix(index));
  for (const Unit& unit : light.units) {
    if (!kept(unit)) continue;
    dev.compilePipelines(unit.pipelines);
    if (unit.kind == Unit::Kind::Shadow) {
      // A preparation makes what its technique declared (a counting pass's
      // maps and lists) and runs frames: the memory guard sees it first.
      FramePlanner::of(dev).guardMemory(light.shadowIds, preparing("shadow", light.shadow->name()));
      light.shadow->prepare(dev);
      preparations_.push_back(lightPrefix(index) + light.shadow->name() + ".prepare");
    } else if (unit.kind == Unit::Kind::Oit && light.oit->needsPrepare()) {
      FramePlanner::of(dev).guardMemory(light.oitIds, preparing("transparency", light.oit->name()));
      // The transparency technique sizes itself against the opaque depth,
      // drawn by the nodes before its own.
      if (light.shading.drawsMesh()) {
        FrameGraph before(resourceNamer(dev));
        for (std::size_t n = 0; n < unit.firstNode; ++n) before.add(graph_.nodes()[n]);
        const auto opaque = before.compile({GraphResource::of(depth_)});
        dev.beginFrame();
        for (const auto* p : opaque) p->execute();
        dev.endFrame();
      }
      light.oit->prepare(dev);
      preparations_.push_back(lightPrefix(index) + light.oit->name() + ".prepare");
    }
  }
}

// An extra light's colour added into the frame's: blend One, One on colour,
// the frame's alpha kept.
void Renderer::addSumPass() {
  if (lights_.size() < 2) return;
  std::vector<Pass> passes;
  for (std::size_t i = 1; i < lights_.size(); ++i)
    passes.push_back(Pass("lights.sum")
                         .color(color_, LoadOp::Load)
                         .sample(SB_SLOT_LIGHTS_SUM_COLOR, lights_[i]->color));
  const BlendState add = {true,         BlendFactor::One,  BlendFactor::One,
                          BlendOp::Add, BlendFactor::Zero, BlendFactor::One,
                          BlendOp::Add};
  sumPipeline_ = fullScreenPipeline(dev_, passes[0], "lights.sum", "renderer",
                                    "render/common/lights_sum.frag", {}, {add});
  graph_.add("lights.sum", passes, [this, passes] {
    for (const Pass& p : passes) p.draw(dev_, sumPipeline_, 3);
  });
}

std::vector<GraphResource> Renderer::resources(const Outputs& outputs) const {
  std::vector<GraphResource> r;
  for (const auto& o : outputs) {
    if (o == Output::Color)
      r.push_back(GraphResource::of(color_));
    else if (o == Output::Visibility && wantVisibility_)
      r.push_back(GraphResource::of(visibility_.image()));
    else if (o == Output::Probe && wantProbe_)
      r.push_back(GraphResource::of(probe_.values()));
    else
      throw DeviceError("renderer: output '" + outputName(o) + "' was not set up");
  }
  return r;
}

void Renderer::upload(const Scene& scene) {
  // --geometry compute: the strands' buffers are the generation pass's; the CPU's
  // strands are not uploaded.
  const bool generated = settings_.geometry == GeometryPath::Compute;
  if (generated) {
    // Made at once, before the techniques are set up: some read the strands back
    // then (the opacity maps' depth range from the light).
    const uint32_t first = dev_.nextHandleId();
    generation_.setup(dev_, scene, gpu_);
    FramePlanner::of(dev_).guardMemory(
        dev_.resourceIdsFrom(first),
        "this run (at least: the groom and the strands made from it on the device)");
    generation_.run(dev_);
  }
  // --geometry mesh: only the groom is on the device (Geometry::strandVertexShader).
  const bool meshPath = settings_.geometry == GeometryPath::Mesh;
  if (meshPath) {
    uploadMeshGroom(dev_, scene, gpu_);
    gpu_.hostPoints = &scene.strands.points;  // for the light's depth range; reset after setup
  }
  static const Strands kNone;
  const Strands& st = generated || meshPath ? kNone : scene.strands;
  std::vector<glm::vec4> points(st.points.size()), colors(st.points.size());
  glm::vec3 lastColor(0.0f);
  float lastAlpha = 1.0f;
  for (std::size_t i = 0; i < st.points.size(); ++i) {
    // World strands whose file gives no width: 0, the view's fallback (the path reference's
    // width for them too), not the loader's stand-in.
    const bool own = !st.thicknessFallback || settings_.primitive != Primitive::World;
    const float thickness = i < st.thickness.size() && own ? st.thickness[i] : 0.0f;
    const float transparency = i < st.transparency.size() ? st.transparency[i] : 0.0f;
    const glm::vec3 c = i < st.colors.size() ? st.colors[i] : scene.hairColor;
    points[i] = glm::vec4(st.points[i], thickness);
    colors[i] = glm::vec4(c, scene.hairAlpha * (1.0f - transparency));
    // A fibre that defines the light it stops (chiang:opacity=fibre) has that opacity for the
    // camera too, in place of the scene's alpha and transparency (the tracer's rung 2 knows
    // only the fibre; the shading divides the colour by the same); strands mostly share a colour.
    if (settings_.shading.fibreShadowAlpha) {
      if (i == 0 || c != lastColor) lastAlpha = settings_.shading.fibreShadowAlpha(c);
      lastColor = c;
      colors[i].a = lastAlpha;
    }
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

  if (!generated && !meshPath) {
    gpu_.points =
        makeBuffer(dev_, "scene.points", points.data(), points.size() * sizeof(glm::vec4));
    gpu_.colors =
        makeBuffer(dev_, "scene.colors", colors.data(), colors.size() * sizeof(glm::vec4));
    gpu_.segments =
        makeBuffer(dev_, "scene.segments", segments.data(), segments.size() * sizeof(uint32_t));
    gpu_.segmentCount = static_cast<uint32_t>(segments.size());
  }
  gpu_.meshPositions = makeBuffer(dev_, "scene.mesh_positions", positions.data(),
                                  positions.size() * sizeof(glm::vec4));
  gpu_.meshNormals =
      makeBuffer(dev_, "scene.mesh_normals", normals.data(), normals.size() * sizeof(glm::vec4));
  gpu_.meshIndices =
      makeBuffer(dev_, "scene.mesh_indices", m.indices.data(), m.indices.size() * sizeof(uint32_t));
  gpu_.meshTriangles = static_cast<uint32_t>(m.triangleCount());
  gpu_.hairAlpha = scene.hairAlpha;
  gpu_.shadowAlpha = settings_.shading.shadowAlpha(scene);
  gpu_.bounds = scene.bounds();
}

std::vector<std::string> Renderer::graphPasses() const {
  std::vector<std::string> names;
  for (const auto* p : passes_) names.push_back(p->name);
  return names;
}

std::vector<std::string> Renderer::graphPasses(const Outputs& outputs) const {
  std::vector<std::string> names;
  for (const auto* p : graph_.compile(resources(outputs))) names.push_back(p->name);
  return names;
}

std::set<uint32_t> Renderer::graphResources(const Outputs& outputs) const {
  std::set<uint32_t> ids;
  for (const auto* p : graph_.compile(resources(outputs))) {
    for (const auto& r : p->reads) ids.insert(r.id);
    for (const auto& r : p->writes) ids.insert(r.id);
  }
  return ids;
}

std::vector<PassTime> Renderer::renderFrame() { return run(passes_); }

std::vector<PassTime> Renderer::renderFrame(const Outputs& outputs) {
  return run(graph_.compile(resources(outputs)));
}

std::vector<PassTime> Renderer::run(const std::vector<const PassNode*>& passes) {
  GroupScope owned(dev_, group_);
  dev_.beginFrame();
  FramePlanner& planner = FramePlanner::of(dev_);
  std::vector<Owner> owners;  // of each pass begun, in order
  const PassNode* first = graph_.nodes().data();
  for (const auto* p : passes) {
    // An extra light's passes carry its prefix; the sum is the frame's.
    const auto index = static_cast<std::size_t>(p - first);
    std::size_t light = 0;
    while (light < lights_.size() && index >= lights_[light]->endNode) ++light;
    LabelScope scope(dev_, lightPrefix(light < lights_.size() ? light : 0));
    // The device times each pass the node begins, in order: they are the node's owner's.
    const std::size_t before = planner.passesBegun();
    p->execute();
    owners.insert(owners.end(), planner.passesBegun() - before, ownerOf(index));
  }
  dev_.endFrame();
  lastTimings_ = dev_.lastFrameTimings();
  if (owners.size() != lastTimings_.size())
    throw std::logic_error("renderer: " + std::to_string(lastTimings_.size()) + " passes timed, " +
                           std::to_string(owners.size()) + " begun");
  std::vector<PassTime> out;
  for (std::size_t i = 0; i < lastTimings_.size(); ++i) {
    const PassTiming& t = lastTimings_[i];
    auto it =
        std::find_if(out.begin(), out.end(), [&](const PassTime& x) { return x.name == t.name; });
    if (it == out.end()) it = out.insert(out.end(), {t.name, owners[i], 0.0, 0, {}});
    it->ms += t.ms;
    ++it->executions;
    it->work += t.work;
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
  std::vector<std::string> all;
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    const std::string who = i == 0 ? "" : "light " + std::to_string(i + 1) + ": ";
    for (auto& w : lights_[i]->shadow->warnings(dev_)) all.push_back(who + w);
    for (auto& w : lights_[i]->oit->warnings(dev_)) all.push_back(who + w);
  }
  return all;
}

std::vector<Counter> Renderer::counters() {
  std::vector<Counter> all;
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    for (Counter& c : lights_[i]->shadow->counters(dev_))
      all.push_back({lightPrefix(i) + c.name, c.value});
    for (Counter& c : lights_[i]->oit->counters(dev_))
      all.push_back({lightPrefix(i) + c.name, c.value});
  }
  return all;
}

}  // namespace sb
