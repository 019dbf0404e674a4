// Puts a frame together: the scene on the device, the shadow technique's
// passes and the final shading, as a frame graph culled to the requested
// outputs. Runs frames and reads back the image.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "techniques/common/technique.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

class Renderer {
 public:
  Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
           std::unique_ptr<ShadowTechnique> shadow,
           const std::set<std::string>& outputs = {"color"});
  // The passes that run, in order (those no output needs are left out).
  std::vector<std::string> passNames() const;
  // Records and runs one frame; returns its per-pass timings.
  std::vector<PassTiming> renderFrame();
  // The colour target: RGBA32F, rows bottom-up (row 0 = NDC y=-1).
  std::vector<uint8_t> readColor();
  const GpuScene& gpuScene() const { return gpu_; }

 private:
  void upload(const Scene& scene);

  Device& dev_;
  RenderSettings settings_;
  GpuScene gpu_;
  std::unique_ptr<ShadowTechnique> shadow_;
  KajiyaKayShading shading_;
  Texture color_, depth_;
  FrameGraph graph_;
  std::vector<const PassNode*> passes_;
};

}  // namespace sb
