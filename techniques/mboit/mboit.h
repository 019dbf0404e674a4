// Moment-based order-independent transparency (Muenstermann, Krumpen, Klein &
// Peters 2018, PACMCGIT 1(1), article 7): the two additive geometry passes of
// the paper and a full-screen resolve.
//   mboit.moments:    b0 = sum A_i and b_k = sum A_i z_i^k (k = 1..2n), A_i =
//                     -ln(1 - alpha_i), z the log-warped view depth
//   mboit.accumulate: sum (c a T(z), a T(z)) with T(z) reconstructed from the
//                     moments (mboit_math.glsl, the paper's bias)
//   mboit.resolve:    the normalised average times 1 - e^-b0, over the opaque colour
// Power moments 4, 6 or 8, in 16-bit (RGBA16F) or 32-bit (RGBA32F) targets;
// b0 stays R32F as in the paper's code. The paper's 16-bit variant quantises
// into UNORM16 after an affine change of basis; here 16 bits means half floats
// (the bias of the paper's 16-bit row is used), which the report says.
#pragma once

#include "render/common/hair_oit.h"
#include "render/common/technique.h"

namespace sb {

class OptionReader;

class MomentOit : public KeptInputsOit {
 public:
  struct Options {
    int moments = 6;    // 4, 6 or 8 real moments beyond b0 (trig: 2, 3, 4 complex)
    bool trig = false;  // trigonometric instead of power moments
    int bits = 32;      // 16 or 32
  };
  explicit MomentOit(Options o) : o_(o) {}
  std::string name() const override { return "mboit"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  // The additive targets after a frame: b0, (b1..b4), (b5..b8) if drawn and the
  // accumulated (c a T, a T), for tests comparing the backends stage by stage.
  std::vector<Texture> targets() const { return {b0_, low_, high_, accum_}; }

 private:
  Pass momentsPass() const;
  Pass accumulatePass() const;
  Pass resolvePass() const;
  bool highTarget() const { return o_.moments > 4; }

  Options o_;
  Buffer params_;
  Texture b0_, low_, high_, accum_;
  Pipeline moments_, accumulate_, resolve_;
};

}  // namespace sb
