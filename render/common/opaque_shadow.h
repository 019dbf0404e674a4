// The opaque mesh seen from the light, for every shadow technique: pass
// "<technique>.opaque" draws the mesh into a depth map; lookups call opaqueVisibility()
// (opaque_shadow.glsl). Without a mesh it creates nothing and adds no pass.
#pragma once

#include "render/common/shader_library.h"
#include "render/common/technique.h"

namespace sb {

class OpaqueShadow {
 public:
  static constexpr uint32_t kBinding = SB_SLOT_OPAQUE_SHADOW;
  // lightViewUbo: the light's ViewUniforms for the same size.
  void setup(Device& dev, const GpuScene& scene, uint32_t size, Buffer lightViewUbo,
             const std::string& technique);
  void addPass(FrameGraph& graph, Device& dev);
  bool active() const { return bool(depth_); }
  // Adds the mesh's shadow (its define, and the map when there is a mesh) to a lookup.
  void addTo(ShadowLookup& lookup) const;

 private:
  Pass pass() const;

  const GpuScene* scene_ = nullptr;
  std::string technique_;
  Buffer lightView_;
  Texture depth_;
  Pipeline pipeline_;
};

// A shadow technique that draws from the light into maps of size x size
// texels, and what it keeps from setup(): the scene, the settings, the light's
// view at the map size (uniform buffer "<name>.light_view") and the opaque
// mesh's shadow drawn with that view.
class LightMapShadow : public ShadowTechnique {
 protected:
  // Keeps the scene and settings, creates the light's view buffer and sets up
  // the opaque shadow; returns the light's view.
  ViewUniforms setupLight(Device& dev, const GpuScene& scene, const RenderSettings& s,
                          uint32_t size);

  const GpuScene* scene_ = nullptr;
  RenderSettings settings_;
  Buffer lightView_;
  OpaqueShadow opaque_;
};

}  // namespace sb
