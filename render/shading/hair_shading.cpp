#include "render/shading/hair_shading.h"

#include <algorithm>
#include <cmath>

#include "techniques/chiang/chiang.h"
#include "render/common/shader_library.h"
#include "techniques/chiang/dual.h"
#include "techniques/kajiya_kay/kajiya_kay.h"
#include "techniques/marschner/marschner.h"
#include "techniques/sadeghi/sadeghi.h"
#include "render/shading/slots.h"

namespace sb {

glm::vec3 HairShading::direct(const ShadingModel& m, glm::vec3 T, glm::vec3 L, glm::vec3 V,
                              glm::vec3 c) {
  if (m.kind == ShadingKind::KajiyaKay) {
    const glm::vec2 kk = glsl::kajiyaKay(T, L, V, m.material.z);
    return m.material.x * kk.x * c + glm::vec3(m.material.y * kk.y);
  }
  if (m.kind == ShadingKind::Chiang)  // over the fibre's opacity where it is the strand's alpha
    return chiangShade(m, T, L, V, c) / (m.fibreShadowAlpha ? m.fibreShadowAlpha(c) : 1.0f);
  const float tl = glm::dot(T, L);
  const float diffuse = std::sqrt(std::max(0.0f, 1.0f - tl * tl));
  const glm::vec3 specular =
      m.kind == ShadingKind::Marschner
          ? glsl::marschner(T, L, V, c, m.shift, m.width) * diffuse
          : glsl::sadeghi(T, L, V, c, m.shift, m.width, m.intensity, m.glintWidth);
  return m.material.x * diffuse * c + m.material.y * specular;
}

float HairShading::maxRadiance(const RenderSettings& s) {
  // Every light's shading adds up; the ambient term counts once.
  float l = 0;
  auto add = [&l](const Light& light) {
    const glm::vec3 c = light.color * light.intensity;
    l += std::max({c.r, c.g, c.b, 0.0f});
  };
  add(s.light);
  for (const Light& e : s.extraLights) add(e);
  const glm::vec4 m = s.shading.material;
  const float ambient = s.ambient ? 1.0f : 0.0f;
  const float hair = ambient * m.w + (m.x + m.y * s.shading.maxSpecular()) * l;
  const float albedo = std::max({kMeshMaterial.r, kMeshMaterial.g, kMeshMaterial.b});
  const float mesh = albedo * (ambient * kMeshMaterial.w + l);
  return std::max({hair, mesh, s.background.r, s.background.g, s.background.b});
}

void HairShading::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
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
  u.hairMaterial = s.shading.material;
  u.meshMaterial = kMeshMaterial;
  if (!s.ambient) u.hairMaterial.w = u.meshMaterial.w = 0;  // an extra light's shading
  u.sceneParams = glm::vec4(scene.hairAlpha, scene.shadowAlpha, s.shading.glintWidth, 0);
  u.lobeShift = s.shading.shift;
  u.lobeWidth = s.shading.width;
  u.lobeIntensity = s.shading.intensity;
  shadingUbo_ = dev.createBuffer({"shading.params", "frame", BufferUsage::Uniform, sizeof u}, &u);
  if (s.shading.kind == ShadingKind::Chiang) {
    // Dual scattering reads chiang's table with its own appended (techniques/chiang/dual.glsl).
    const std::vector<float>& table = s.shading.dualScattering
                                          ? dualTable(s.shading)
                                          : chiangLobeTable(s.shading.betaN, s.shading.eta);
    lobeTable_ = dev.createBuffer(
        {"shading.lobe_table", "frame", BufferUsage::Storage, table.size() * sizeof(float)},
        table.data());
  }

  if (scene.hasMesh()) {
    const ShaderCode vert = Geometry::meshVertexShader();
    const ShaderCode frag = loadShader("render/shading/mesh.frag", hairDefines());
    PipelineDesc d = meshPass().pipeline(dev, "shading.mesh", "kajiya_kay+" + shadow.name());
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
  defs.defines.push_back(
      {"SB_SHADING_MODEL", std::to_string(static_cast<int>(settings_.shading.kind))});
  if (settings_.shading.kind == ShadingKind::Chiang && settings_.shading.fibreShadowAlpha)
    defs.defines.push_back({"SB_FIBRE_OPACITY", "1"});
  if (settings_.shading.dualScattering) defs.defines.push_back({"SB_DUAL_SCATTERING", "1"});
  return defs;
}

Inputs HairShading::hairInputs() const {
  Inputs in = Geometry::inputs(*scene_, viewUbo_);
  in.uniform(bind::kShading, shadingUbo_).add(shadow_->lookup().inputs);
  if (lobeTable_) in.readStorage(SB_SLOT_SHADING_TABLE, lobeTable_);
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
