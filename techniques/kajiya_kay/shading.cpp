#include "techniques/kajiya_kay/shading.h"

#include "techniques/common/shader_library.h"

namespace sb {

void KajiyaKayShading::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                             const ShadowTechnique& shadow, Texture color, Texture depth) {
  scene_ = &scene;
  shadow_ = &shadow;
  settings_ = s;
  color_ = color;
  depth_ = depth;
  const ViewUniforms view = cameraView(s);
  viewUbo_ = dev.createBuffer({"shading.view", "frame", BufferUsage::Uniform, sizeof view}, &view);
  ShadingUniforms u{};
  u.eyePos = glm::vec4(s.camera.eye, 1);
  u.lightPos = s.light.type == LightType::Point ? glm::vec4(s.light.position, 1)
                                                : glm::vec4(-glm::normalize(s.light.direction), 0);
  u.lightColor = glm::vec4(s.light.color * s.light.intensity, 1);
  u.hairMaterial = glm::vec4(0.8f, 0.35f, 40.0f, 0.12f);
  u.meshMaterial = glm::vec4(0.75f, 0.72f, 0.68f, 0.15f);
  u.sceneParams = glm::vec4(scene.hairAlpha, scene.shadowAlpha, 0, 0);
  shadingUbo_ = dev.createBuffer({"shading.params", "frame", BufferUsage::Uniform, sizeof u}, &u);

  ShaderDefines defs;
  defs.aliases["shadow"] = shadow.lookupShader();
  PipelineDesc d;
  d.technique = "kajiya_kay+" + shadow.name();
  d.colorFormats = {Format::RGBA32F};
  d.hasDepth = d.depthTest = d.depthWrite = true;
  d.depthCompare = CompareOp::Less;
  d.bindings = Geometry::slots();
  d.bindings.push_back({bind::kShading, BindingKind::UniformBuffer});
  for (const auto& slot : shadow.lookupSlots()) d.bindings.push_back(slot);
  if (scene.hasHair()) {
    const ShaderCode vert = Geometry::strandVertexShader(s);
    const ShaderCode frag = loadShader("techniques/kajiya_kay/hair.frag", defs);
    d.name = "shading.hair";
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    hairPipeline_ = dev.createPipeline(d);
  }
  if (scene.hasMesh()) {
    const ShaderCode vert = Geometry::meshVertexShader();
    const ShaderCode frag = loadShader("techniques/kajiya_kay/mesh.frag", defs);
    d.name = "shading.mesh";
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Topology::Triangles;
    meshPipeline_ = dev.createPipeline(d);
  }
}

std::vector<Binding> KajiyaKayShading::bindings() const {
  auto b = Geometry::bindings(*scene_, viewUbo_);
  b.push_back(Binding::buf(bind::kShading, shadingUbo_));
  for (const auto& x : shadow_->lookupBindings()) b.push_back(x);
  return b;
}

PassDesc KajiyaKayShading::passDesc(const std::string& name, bool clear) const {
  PassDesc pass;
  pass.name = name;
  const glm::vec3 bg = settings_.background;
  pass.color = {{color_, clear ? LoadOp::Clear : LoadOp::Load, {bg.r, bg.g, bg.b, 1.0f}}};
  pass.depth = {depth_, clear ? LoadOp::Clear : LoadOp::Load, 1.0f};
  pass.sampledTextures = shadow_->lookupTextures();
  return pass;
}

void KajiyaKayShading::addPasses(FrameGraph& graph, Device& dev) {
  std::vector<std::string> reads = shadow_->lookupReads();
  // The first pass clears the targets; a scene without a mesh has no mesh pass.
  if (meshPipeline_) {
    graph.add({"shading.mesh", reads, {"color", "depth"}, [this, &dev] {
                 dev.beginPass(passDesc("shading.mesh", true));
                 dev.draw(meshPipeline_, bindings(), scene_->meshTriangles * 3);
                 dev.endPass();
               }});
  }
  if (hairPipeline_) {
    const bool clear = !meshPipeline_;
    if (!clear) {
      reads.push_back("color");
      reads.push_back("depth");
    }
    graph.add({"shading.hair", reads, {"color", "depth"}, [this, &dev, clear] {
                 dev.beginPass(passDesc("shading.hair", clear));
                 dev.draw(hairPipeline_, bindings(),
                          Geometry::strandVertexCount(*scene_, settings_));
                 dev.endPass();
               }});
  }
}

}  // namespace sb
