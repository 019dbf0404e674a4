#pragma once

#include "render/common/technique.h"

namespace sb {

class HairShading;

// Output "visibility": an R32F image of shadowVisibility() at the nearest hair
// or mesh fragment of every pixel (-1 where there is none). Its passes run
// only when a run asks for visibility error.
class VisibilityOutput {
 public:
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading);
  void addPasses(FrameGraph& graph, Device& dev);
  Texture image() const { return image_; }

 private:
  Pass pass() const;

  const GpuScene* scene_ = nullptr;
  const HairShading* shading_ = nullptr;
  RenderSettings settings_;
  Texture image_, depth_;
  Pipeline hair_, mesh_;
};

}  // namespace sb
