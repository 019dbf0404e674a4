// Multi-layer alpha blending (Salvi & Vaidyanathan 2014, I3D): L layers per
// pixel, each fragment inserted in depth order and the two farthest merged
// when they overflow (mlab_math.glsl). The paper does this in the geometry
// pass with ordered per-pixel read-modify-write (pixel synchronisation:
// GL_ARB_fragment_shader_interlock / VK_EXT_fragment_shader_interlock). The
// device says whether it has it (DeviceInfo::fragmentShaderInterlock); Mesa's
// CPU drivers do not, and no interlock path is written: the only path stores
// the fragments in the A-buffer's lists (with their primitive ids) and merges
// each pixel's fragments in primitive order in a resolve, the order ordered
// interlock guarantees, so the image is the paper's; the timing is marked
// emulated (render JSON "timing_emulated", a warning in the reports) and the
// merges are counted ("emulated_steps": one per fragment merged).
#pragma once

#include "techniques/abuffer/abuffer.h"

namespace sb {

class MlabOit : public ABufferOit {
 public:
  static constexpr int kMaxLayers = 32;  // mlab_math.glsl's SB_MLAB_MAX
  explicit MlabOit(int layers) : ABufferOit(~0ull), layers_(layers) {}
  std::string name() const override { return "mlab"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  std::vector<Counter> counters(Device& dev) override;
  std::string timingEmulated() const override { return emulated_; }

 protected:
  std::string resolveShader() const override { return "techniques/mlab/resolve.comp"; }
  ShaderDefines resolveDefines() const override;

 private:
  int layers_;
  std::string emulated_;
};

}  // namespace sb
