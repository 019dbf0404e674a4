#pragma once

#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

class OptionReader;

// Density clustering (Mertens et al. 2004): per light texel, k-means on the
// hair fragments' depths. "dc.init" finds each texel's depth range (RG32F, min
// blending); then, per iteration, "dc.means" writes the cluster centres (at
// first spread evenly over the range, later the clusters' mean depths) and
// "dc.iterate" draws the hair, each fragment adding (1, z, z^2) (relative to
// the texel's nearest depth) to its nearest cluster's channel of three RGBA32F
// arrays (additive). Each map is an array of a layer per 4 clusters, every
// layer a colour attachment: 8 clusters fill the iterate pass's 6 targets of
// the 8 a pass may have. The lookup spreads each cluster's count uniformly
// over mean +- sqrt(3) sd (dc_math.glsl).
class DensityClusteringShadow : public ShadowTechnique {
 public:
  struct Options {
    uint32_t size = 512;
    float bias = 0.002f;
    uint32_t clusters = 4;  // 1..8: one channel of a layer of each RGBA32F array per cluster
    uint32_t iterations = 2;
  };
  // Reads and validates size, bias, clusters, iterations (InputError).
  static constexpr uint32_t kMaxClusters = 8;  // 2 layers x 3 arrays: 6 colour attachments
  explicit DensityClusteringShadow(const Options& opts) : opts_(opts) {}

  std::string name() const override { return "dc"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;

  // The maps, for tests: range (RG32F), centres, counts, sums, square sums
  // (RGBA32F arrays of layers() layers).
  uint32_t layers() const { return (opts_.clusters + 3) / 4; }
  Texture rangeMap() const { return range_; }
  Texture centreMap() const { return centres_; }
  Texture countMap() const { return counts_; }
  Texture sumMap() const { return sums_; }
  Texture squareMap() const { return squares_; }

 private:
  Pass initPass() const;
  Pass meansPass(bool first) const;
  Pass iteratePass() const;

  Options opts_;
  const GpuScene* scene_ = nullptr;
  RenderSettings settings_;
  Buffer lightView_, params_;
  Texture range_, centres_, counts_, sums_, squares_;
  OpaqueShadow opaque_;
  Pipeline rangePipeline_, firstMeansPipeline_, meansPipeline_, iteratePipeline_;
};

}  // namespace sb
