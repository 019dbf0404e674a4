#pragma once

#include "base/options.h"
#include "render/common/hair_oit.h"

namespace sb {

// The options of depth peeling, declared once (unit.cpp): peel's, which
// peel_classic and dual_peel reuse.
struct PeelOptions {
  uint32_t layers;
  static const OptionTable<PeelOptions>& table();
};

// Exact transparency by depth peeling from the eye, front to back, one layer
// per step (three hair draws: smallest depth, smallest primitive id at that
// depth, shade and accumulate), for as many layers as the deepest pixel holds
// (counted once in prepare(), standing in for an occlusion query per layer),
// capped by layers= (a cap that is reported).
class PeelOit : public PeelingOit {
 public:
  using PeelingOit::PeelingOit;
  std::string name() const override { return "peel"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  std::vector<std::string> warnings(Device& dev) override;

 private:
  Pass stepPass(int step, bool first) const;
  Pass advancePass() const;

  Buffer state_, peeled_, sizeUbo_;
  Pipeline step_[3], advance_;
};

}  // namespace sb
