#pragma once

#include "techniques/common/technique.h"

namespace sb {

class NoShadow : public ShadowTechnique {
 public:
  std::string name() const override { return "none"; }
  void setup(Device&, const GpuScene&, const RenderSettings&) override {}
  void addPasses(FrameGraph&, Device&) override {}
  std::string lookupShader() const override;
  std::vector<std::string> lookupReads() const override { return {}; }
  std::vector<BindingSlot> lookupSlots() const override { return {}; }
  std::vector<Binding> lookupBindings() const override { return {}; }
  std::vector<Texture> lookupTextures() const override { return {}; }
};

}  // namespace sb
