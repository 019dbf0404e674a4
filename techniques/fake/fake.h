#pragma once

#include <array>

#include "render/common/hair_oit.h"
#include "render/common/technique.h"

namespace sb {

// The deep opacity maps paper's "fake transparency" (Yuksel & Keyser 2008,
// section 4: "we divided the set of hair strands into three disjoint subsets.
// Each one of these subsets is rendered separately with no transparency on a
// separate image. The resulting images are then blended to produce the final
// frame."). Strand i goes to subset i mod 3 (interleaved, so each subset
// covers the whole hair); each subset is drawn opaque with its own depth test
// (the opaque mesh's depth drawn first, so the mesh hides hair behind it) into
// its own RGBA32F image, alpha 1 where hair was drawn; a full-screen pass
// blends the three with equal weights over the opaque colour:
//   C = sum_k c_k a_k / 3 + (1 - sum_k a_k / 3) C_dst.
// It ignores the hair's alpha: a pixel covered by all three subsets is the
// average of their nearest strands, whatever the hair's opacity.
class FakeTransparency : public KeptInputsOit {
 public:
  static constexpr uint32_t kSubsets = 3;
  std::string name() const override { return "fake"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;

  // The segments of each subset (for tests).
  const std::array<uint32_t, kSubsets>& subsetSegments() const { return counts_; }

 private:
  Pass subsetPass(uint32_t k) const;
  Pass blendPass() const;

  std::array<Buffer, kSubsets> segments_{};
  std::array<uint32_t, kSubsets> counts_{};
  std::array<Texture, kSubsets> images_{};
  std::array<Texture, kSubsets>
      imagesMs_{};  // --msaa N: the N-sample images, averaged into images_
  Texture depth_;
  Pipeline hairPipeline_, meshPipeline_, blendPipeline_;
};

}  // namespace sb
