#pragma once

#include "render/common/technique.h"

namespace sb {

// Williams (1978): one depth map from the light holding the nearest hair or
// mesh surface; a point behind it is in shadow (binary visibility).
class ShadowMap : public ShadowTechnique {
 public:
  ShadowMap(uint32_t size, float bias) : size_(size), bias_(bias) {}
  std::string name() const override { return "shadowmap"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;

 private:
  Pass pass() const;

  uint32_t size_;
  float bias_;
  const GpuScene* scene_ = nullptr;
  RenderSettings settings_;
  Texture depth_;
  Buffer lightViewUbo_, paramsUbo_;
  Pipeline hairPipeline_, meshPipeline_;
};

}  // namespace sb
