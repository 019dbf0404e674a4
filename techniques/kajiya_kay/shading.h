#pragma once

#include "techniques/common/technique.h"

namespace sb {

struct ShadingUniforms {
  glm::vec4 eyePos;
  glm::vec4 lightPos;
  glm::vec4 lightColor;
  glm::vec4 hairMaterial;  // kd, ks, shininess, ambient
  glm::vec4 meshMaterial;  // rgb, ambient
  glm::vec4 sceneParams;   // hair alpha, shadow alpha
};

// Final shading: the opaque mesh (Lambert) and depth-tested hair (Kajiya-Kay),
// both lit through the shadow technique's lookup. Writes "color" and "depth".
class KajiyaKayShading {
 public:
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const ShadowTechnique& shadow, Texture color, Texture depth);
  void addPasses(FrameGraph& graph, Device& dev);

 private:
  std::vector<Binding> bindings() const;
  PassDesc passDesc(const std::string& name, bool clear) const;

  const GpuScene* scene_ = nullptr;
  const ShadowTechnique* shadow_ = nullptr;
  RenderSettings settings_;
  Texture color_, depth_;
  Buffer viewUbo_, shadingUbo_;
  Pipeline hairPipeline_, meshPipeline_;
};

}  // namespace sb
