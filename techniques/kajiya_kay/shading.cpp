#include "techniques/kajiya_kay/shading.h"

#include <algorithm>

#include "techniques/common/shader_library.h"

namespace sb {

float KajiyaKayShading::maxRadiance(const RenderSettings& s) {
  const glm::vec3 light = s.light.color * s.light.intensity;
  const float l = std::max({light.r, light.g, light.b, 0.0f});
  const float hair = kHairMaterial.w + (kHairMaterial.x + kHairMaterial.y) * l;
  const float albedo = std::max({kMeshMaterial.r, kMeshMaterial.g, kMeshMaterial.b});
  const float mesh = albedo * (kMeshMaterial.w + l);
  return std::max({hair, mesh, s.background.r, s.background.g, s.background.b});
}

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
  u.hairMaterial = kHairMaterial;
  u.meshMaterial = kMeshMaterial;
  u.sceneParams = glm::vec4(scene.hairAlpha, scene.shadowAlpha, 0, 0);
  shadingUbo_ = dev.createBuffer({"shading.params", "frame", BufferUsage::Uniform, sizeof u}, &u);

  if (scene.hasMesh()) {
    const ShaderCode vert = Geometry::meshVertexShader();
    const ShaderCode frag = loadShader("techniques/kajiya_kay/mesh.frag", hairDefines());
    PipelineDesc d;
    d.name = "shading.mesh";
    d.technique = "kajiya_kay+" + shadow.name();
    d.vertex = &vert;
    d.fragment = &frag;
    d.colorFormats = {Format::RGBA32F};
    d.hasDepth = d.depthTest = d.depthWrite = true;
    d.depthCompare = CompareOp::Less;
    d.bindings = hairSlots();
    meshPipeline_ = dev.createPipeline(d);
  }
}

ShaderDefines KajiyaKayShading::hairDefines() const {
  ShaderDefines defs = shadow_->lookupDefines();
  defs.aliases["shadow"] = shadow_->lookupShader();
  return defs;
}

std::vector<BindingSlot> KajiyaKayShading::hairSlots() const {
  auto slots = Geometry::slots();
  slots.push_back({bind::kShading, BindingKind::UniformBuffer});
  for (const auto& slot : shadow_->lookupSlots()) slots.push_back(slot);
  return slots;
}

std::vector<Binding> KajiyaKayShading::hairBindings() const {
  auto b = Geometry::bindings(*scene_, viewUbo_);
  b.push_back(Binding::buf(bind::kShading, shadingUbo_));
  for (const auto& x : shadow_->lookupBindings()) b.push_back(x);
  return b;
}

void KajiyaKayShading::addMeshPass(FrameGraph& graph, Device& dev) {
  if (!meshPipeline_) return;
  graph.add({"shading.mesh", shadowReads(), {"color", "depth"}, [this, &dev] {
               PassDesc pass;
               pass.name = "shading.mesh";
               const glm::vec3 bg = settings_.background;
               pass.color = {{color_, LoadOp::Clear, {bg.r, bg.g, bg.b, 1.0f}}};
               pass.depth = {depth_, LoadOp::Clear, 1.0f};
               pass.sampledTextures = sampledTextures();
               dev.beginPass(pass);
               dev.draw(meshPipeline_, hairBindings(), scene_->meshTriangles * 3);
               dev.endPass();
             }});
}

}  // namespace sb
