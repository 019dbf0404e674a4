// Stochastic transparency (Enderton, Sintorn, Shirley & Luebke 2010), the
// unbiased three-pass version with alpha correction:
//   1. alpha: prod(1 - a) exactly (multiplicative blending);
//   2. depth: each hair fragment covers a random subset of the pixel's S
//      samples, each with probability alpha (stochastic_math.glsl), and keeps
//      per covered sample the nearest depth;
//   3. accumulate: the hair again, adding (a c, a) times the fraction of the S
//      samples it is not behind: its estimated visibility prod(1 - a_j);
// and a full-screen resolve with the paper's alpha correction.
// The S sample depths are a storage buffer (S words per pixel, atomicMin of
// the depth's bits), not a multisampled depth target: Mesa's CPU drivers
// rasterize lines in a multisampled pass with one depth for the whole pixel
// (GL, multisample rasterization off for lines as Vulkan's Bresenham lines:
// the sample mask did not limit the depth written; Vulkan: one depth test for
// every sample), so the estimate had 1 sample per group of m on Vulkan and a
// bias GL's samples did not reduce. The buffer gives every sample its own
// depth for lines and ribbons alike, S up to 64 in one pass, the same on both
// APIs. Memory: 4 S bytes per pixel + the accumulation (16) and alpha (4).
#pragma once

#include "render/common/hair_oit.h"
#include "render/common/technique.h"

namespace sb {

class StochasticOit : public KeptInputsOit {
 public:
  struct Options {
    uint32_t samples = 8;
    uint32_t seed = 1;
  };
  static constexpr uint32_t kMaxSamples = 64;
  explicit StochasticOit(Options o) : options_(o) {}
  std::string name() const override { return "stochastic"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;

 private:
  Pass alphaPass() const;
  Pass depthPass() const;
  Pass accumulatePass() const;
  Pass resolvePass() const;

  Options options_;
  Buffer params_;  // (seed, samples)
  Buffer depths_;  // S sample depths per pixel (uint bits of the window depth)
  Texture accum_, alpha_;
  Pipeline alphaPipe_, depthPipe_, accumulatePipe_, resolvePipe_;
};

}  // namespace sb
