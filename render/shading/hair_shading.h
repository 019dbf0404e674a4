#pragma once

#include "render/common/shader_library.h"
#include "render/common/shading_uniforms.h"
#include "render/common/technique.h"

namespace sb {

// Final shading from the camera: the opaque mesh (Lambert, pass "shading.mesh")
// and what every hair pass of a transparency technique needs to shade hair with
// the model chosen by --shading (its folder's shading.glsl, bound as <shading>) through the
// shadow technique's lookup (hair_shading.glsl).
class HairShading {
 public:
  // Mesh: albedo, ambient (hair: the shading model's material).
  static constexpr glm::vec4 kMeshMaterial{0.75f, 0.72f, 0.68f, 0.15f};
  // The brightest any shaded fragment or the background can be (hair colour
  // <= 1, visibility <= 1): a bound every composited pixel must stay under.
  static float maxRadiance(const RenderSettings& s);

  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const ShadowTechnique& shadow, Texture color, Texture depth);
  // Writes the colour and depth targets (clearing them); only when the scene has a mesh.
  void addMeshPass(FrameGraph& graph, Device& dev);
  bool drawsMesh() const { return bool(meshPipeline_); }

  // For hair passes: the shader defines (<shadow> bound) and the inputs
  // (geometry, shading uniforms, the shadow lookup's inputs).
  ShaderDefines hairDefines() const;
  Inputs hairInputs() const;
  Buffer viewUbo() const { return viewUbo_; }
  const ShadowTechnique& shadow() const { return *shadow_; }

 private:
  Pass meshPass() const;

  const GpuScene* scene_ = nullptr;
  const ShadowTechnique* shadow_ = nullptr;
  RenderSettings settings_;
  Texture color_, depth_;
  Buffer viewUbo_, shadingUbo_, modelUbo_;
  std::vector<std::pair<int, Buffer>> tables_;  // the shading model's, at their slots
  Pipeline meshPipeline_;
};

}  // namespace sb
