#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"
#include "techniques/exact/exact.h"

namespace sb {

// Deep shadow maps (Lokovic & Veach 2000): per light texel, the visibility
// function kept as a piecewise-linear curve within `epsilon` of the exact one,
// by the paper's greedy compression (techniques/dsm/dsm_math.glsl). The
// exact function comes from the light-space fragment lists the exact
// technique builds and sorts (ExactShadow, method abuffer: those lists are
// the paper's per-pixel surface samples); a compute pass compresses each
// texel's list into its nodes, and the lookup searches the curve. Memory:
// each texel has room for min(2 n, max_nodes) nodes (n its fragments, 2 n
// what epsilon = 0 needs); the nodes actually kept are counted per texel
// (counters: nodes min / mean / max, kept bytes).
class DeepShadowMaps : public LightMapShadow {
 public:
  struct Options {
    float epsilon = 0.01f;
    uint32_t maxNodes = 64;
    uint32_t size = 512;
    float bias = 0.002f;
  };
  explicit DeepShadowMaps(const Options& o);
  std::string name() const override { return "dsm"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void prepare(Device& dev) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::optional<DepthComplexity> depthComplexity() const override { return complexity_; }
  std::vector<std::string> warnings(Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;

  // After a frame: the nodes kept per texel.
  std::vector<uint32_t> keptNodes(Device& dev);

 private:
  Pass compressPass() const;

  Options opt_;
  ExactShadow lists_;
  Buffer params_, compress_, kept_, offsets_, nodes_, status_;
  std::size_t capacity_ = 0;    // node slots in all
  DepthComplexity complexity_;  // the lists' (counted in prepare)
  Pipeline pipeline_;
};

}  // namespace sb
