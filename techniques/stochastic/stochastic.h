// Stochastic transparency (Enderton, Sintorn, Shirley & Luebke 2010), the
// unbiased three-pass version with alpha correction, on multisampled targets:
//   1. depth: a multisampled depth pass where each hair fragment covers a
//      random subset of the samples (gl_SampleMask), each with probability
//      alpha (stochastic_math.glsl);
//   2. accumulate: the hair again, depth-tested per sample against it (Less
//      or equal, no write), adding (a c, a) into a multisampled RGBA32F target
//      that the pass resolves (averages): each fragment weighted by the
//      fraction of samples it passes, its estimated visibility;
//   3. alpha: prod(1 - a) exactly (multiplicative blending, one sample);
// and a full-screen resolve with the paper's alpha correction.
// S samples per pixel (`samples`) are made of groups of m multisampled
// samples, m the largest count the device has that divides S (the paper
// combines passes the same way for more samples than the hardware has):
// S/m groups of passes 1-2, their resolved sums added ("stochastic.sum").
// `seed` changes every random draw. Memory: the m-sample depth and colour
// targets, the resolved colour, the sum and the total alpha.
#pragma once

#include "techniques/common/technique.h"

namespace sb {

class StochasticOit : public OitTechnique {
 public:
  struct Options {
    uint32_t samples = 8;
    uint32_t seed = 1;
  };
  static Options readOptions(const class OptionReader& o);
  explicit StochasticOit(Options o) : options_(o) {}
  std::string name() const override { return "stochastic"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const KajiyaKayShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  // The multisampled samples per group and the groups (m, S/m).
  uint32_t samplesPerGroup() const { return perGroup_; }
  uint32_t groups() const { return options_.samples / perGroup_; }

 private:
  Pass alphaPass() const;
  Pass depthPass(uint32_t group) const;
  Pass accumulatePass(uint32_t group) const;
  Pass sumPass(uint32_t group) const;
  Pass resolvePass() const;
  Inputs hairInputs(uint32_t group) const;

  Options options_;
  uint32_t perGroup_ = 1;
  const GpuScene* scene_ = nullptr;
  const KajiyaKayShading* shading_ = nullptr;
  RenderSettings settings_;
  OitTargets targets_;
  std::vector<Buffer> params_;  // one per group: (seed, group, samples, opaque)
  Texture depthMs_, accumMs_, accum_, sum_, alpha_;
  Pipeline alphaPipe_, depthPipe_, accumulatePipe_, sumPipe_, resolvePipe_;
};

}  // namespace sb
