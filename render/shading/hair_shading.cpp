#include "render/shading/hair_shading.h"

#include <algorithm>
#include <cmath>

#include "render/common/shader_library.h"
#include "render/common/unit.h"

namespace sb {

float HairShading::maxRadiance(const RenderSettings& s) {
  // Every light's shading adds up; the ambient term counts once.
  float l = 0;
  auto add = [&l](const Light& light) {
    const glm::vec3 c = light.color * light.intensity;
    l += std::max({c.r, c.g, c.b, 0.0f});
  };
  add(s.light);
  for (const Light& e : s.extraLights) add(e);
  const float ambient = s.ambient ? 1.0f : 0.0f;
  const float hair = ambient * s.shading.ambient + s.shading.maxDirect * l;
  const float albedo = std::max({kMeshMaterial.r, kMeshMaterial.g, kMeshMaterial.b});
  const float mesh = albedo * (ambient * kMeshMaterial.w + l);
  return std::max({hair, mesh, s.background.r, s.background.g, s.background.b});
}

void HairShading::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                        const ShadowTechnique& shadow, Texture color, Texture depth) {
  scene_ = &scene;
  shadow_ = &shadow;
  settings_ = s;
  // Settings made in code rather than from a request: the registry's default model.
  if (settings_.shading.shader.empty())
    settings_.shading = ShadingModel::fromSpec(defaultTechnique(Family::Shading).name);
  color_ = color;
  depth_ = depth;
  const ViewUniforms view = cameraView(s);
  viewUbo_ =
      dev.createBuffer({"shading.view", Owner::Frame, BufferUsage::Uniform, sizeof view}, &view);
  ShadingUniforms u{};
  u.eyePos = glm::vec4(s.camera.eye, 1);
  u.lightPos = s.light.type == LightType::Point ? glm::vec4(s.light.position, 1)
                                                : glm::vec4(-glm::normalize(s.light.direction), 0);
  u.lightColor = glm::vec4(s.light.color * s.light.intensity, 1);
  u.meshMaterial = kMeshMaterial;
  const float ambient =
      s.ambient ? settings_.shading.ambient : 0.0f;  // none in an extra light's shading
  if (!s.ambient) u.meshMaterial.w = 0;
  u.sceneParams = glm::vec4(scene.hairAlpha, scene.shadowAlpha, ambient, 0);
  shadingUbo_ =
      dev.createBuffer({"shading.params", Owner::Frame, BufferUsage::Uniform, sizeof u}, &u);
  // The model's own block and tables (its folder's uniforms.h and slots.h).
  const ShadingModel& model = settings_.shading;
  const std::vector<std::byte>& params = model.params;
  modelUbo_ = dev.createBuffer({"shading.model", Owner::Frame, BufferUsage::Uniform, params.size()},
                               params.data());
  tables_.clear();
  for (const ShadingModel::Table& t : model.tables)
    tables_.push_back(
        {t.slot, dev.createBuffer({"shading.lobe_table", Owner::Frame, BufferUsage::Storage,
                                   t.data->size() * sizeof(float)},
                                  t.data->data())});

  if (scene.hasMesh()) {
    const ShaderCode vert = Geometry::meshVertexShader();
    const ShaderCode frag = loadShader("render/shading/mesh.frag", hairDefines());
    PipelineDesc d = meshPass().pipeline(dev, "shading.mesh", "mesh+" + shadow.name());
    d.vertex = &vert;
    d.fragment = &frag;
    d.depthCompare = CompareOp::Less;
    meshPipeline_ = dev.createPipeline(d);
  }
}

ShaderDefines HairShading::hairDefines() const {
  const ShadowLookup lookup = shadow_->lookup();
  ShaderDefines defs = lookup.defines;
  defs.aliases["shadow"] = lookup.shader;
  defs.aliases["shading"] = settings_.shading.shader;
  return defs;
}

Inputs HairShading::hairInputs() const {
  Inputs in = Geometry::inputs(*scene_, viewUbo_);
  in.uniform(bind::kShading, shadingUbo_)
      .uniform(SB_SLOT_SHADING_MODEL, modelUbo_)
      .add(shadow_->lookup().inputs);
  for (const auto& [slot, table] : tables_) in.readStorage(slot, table);
  return in;
}

Pass HairShading::meshPass() const {
  const glm::vec3 bg = settings_.background;
  return Pass("shading.mesh")
      .color(color_, LoadOp::Clear, {bg.r, bg.g, bg.b, 1.0f})
      .depth(depth_, LoadOp::Clear)
      .inputs(hairInputs());
}

void HairShading::addMeshPass(FrameGraph& graph, Device& dev) {
  if (!meshPipeline_) return;
  graph.add(meshPass(), [this, &dev, p = meshPass()] {
    p.draw(dev, meshPipeline_, scene_->meshTriangles * 3);
  });
}

}  // namespace sb
