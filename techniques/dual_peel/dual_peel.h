// Dual depth peeling (Bavoil & Myers 2008, "Order Independent Transparency
// with Dual Depth Peeling", NVIDIA): each geometry pass peels the nearest and
// the farthest remaining layer at once. A first pass writes (-z, z) with MAX
// blending (the nearest and farthest depth per pixel, RG32F); each peel pass
// then, against the last pass's min/max:
//   - a fragment outside [nearest, farthest] was peeled: it only carries the
//     front accumulation forward;
//   - one strictly inside writes (-z, z) for the next pass;
//   - one at the nearest depth is blended under the front accumulation
//     (front to back), one at the farthest goes to the back layer;
// all three targets blend with MAX (the paper's single blend equation). The
// back layer is blended over a back accumulation after each pass (back to
// front); the final pass composites front, back and the opaque colour.
// Geometry passes: 1 + ceil(layers / 2), layers the deepest pixel's count
// (measured once, standing in for the paper's occlusion query), capped by
// `layers` (reported). Depth ties are lost as in classic peeling (the MAX
// keeps one of them); --oit peel stays the ground truth.
#pragma once

#include "render/common/hair_oit.h"

namespace sb {

class DualPeelOit : public PeelingOit {
 public:
  using PeelingOit::PeelingOit;
  std::string name() const override { return "dual_peel"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  std::vector<std::string> warnings(Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;
  // The peel passes the layers take (ceil(layers / 2)).
  uint32_t peelPasses() const { return (layers_ + 1) / 2; }

 private:
  Pass clearPass() const;
  Pass initPass() const;
  Pass peelPass(uint32_t pass) const;  // 1, 2, ...
  Pass backPass() const;
  Pass finalPass() const;

  Texture depth_[2], front_[2], backTemp_, back_;
  Pipeline init_, peel_, back_blend_, final_;
};

}  // namespace sb
