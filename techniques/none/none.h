#pragma once

#include "render/common/technique.h"

namespace sb {

class NoShadow : public ShadowTechnique {
 public:
  std::string name() const override { return "none"; }
  void setup(Device&, const GpuScene&, const RenderSettings&) override {}
  void addPasses(FrameGraph&, Device&) override {}
  ShadowLookup lookup() const override { return {"techniques/none/lookup.glsl"}; }
};

}  // namespace sb
