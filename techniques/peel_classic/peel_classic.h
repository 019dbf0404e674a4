// Depth peeling as the papers time it (Everitt 2001, "Interactive
// Order-Independent Transparency"): one geometry pass per layer. Each pass
// draws every hair fragment, keeps those strictly behind the previous layer's
// depth (sampled from the last pass's R32F copy: the "second depth test") and
// in front of the opaque depth, and the hardware depth test (Less) keeps the
// nearest of them: the layer. A full-screen pass blends it under what is
// accumulated (front to back), and a last one composites over the opaque
// colour. Fragments at exactly the depth of a peeled one are lost (the second
// test is strict): they are counted (`lost_ties`, from the peeled count per
// pixel against the fragment count) and reported, never silent. The exact,
// tie-breaking peel (--oit peel) stays the ground truth. Layers: the deepest
// pixel's count (measured once, as an occlusion query per layer would stop),
// capped by `layers` (reported).
#pragma once

#include "render/common/hair_oit.h"

namespace sb {

class ClassicPeelOit : public PeelingOit {
 public:
  using PeelingOit::PeelingOit;
  std::string name() const override { return "peel_classic"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  std::vector<std::string> warnings(Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;

 private:
  Pass clearPass() const;
  Pass layerPass(uint32_t layer) const;
  Pass blendPass(uint32_t layer) const;
  Pass compositePass() const;

  Texture layerColor_, layerDepth_[2], peelDepth_, under_, peeled_;
  Pipeline layer_, blend_, composite_;
};

}  // namespace sb
