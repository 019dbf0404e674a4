#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"
#include "techniques/exact/exact.h"

namespace sb {

// Adaptive volumetric shadow maps (Salvi et al. 2010): per light texel a
// transmittance curve of at most `nodes` nodes, built by streaming each hair
// fragment into it and removing the node whose removal changes the area under
// the curve least (techniques/avsm/avsm_math.glsl); the lookup interpolates
// the curve at the receiver's depth.
//
// The paper streams in the light pass with ordered per-texel read-modify-write
// (pixel synchronisation, i.e. fragment-shader interlock). As mlab, no
// interlock path is written (Mesa's CPU drivers have none): the fragments are
// stored in the exact technique's light-space lists, sorted in submission
// order (primitive id, then depth: the order ordered interlock guarantees),
// and a resolve streams each texel's list in that order: the curve is the
// paper's, the timing is not (timingEmulated(): render JSON
// "timing_emulated", counter "emulated_steps").
//
// Memory: the paper's is the nodes (count per texel + nodes x 8 bytes per
// texel, resource "avsm.nodes" and "avsm.count"); the lists are the
// emulation's (resources "exact.*"), counted apart (counters).
class AdaptiveVolumetricShadowMaps : public LightMapShadow {
 public:
  struct Options {
    uint32_t nodes = 8;  // 4, 8 or 16
    uint32_t size = 512;
    float bias = 0.002f;
  };
  explicit AdaptiveVolumetricShadowMaps(const Options& o);
  std::string name() const override { return "avsm"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void prepare(Device& dev) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::optional<DepthComplexity> depthComplexity() const override {
    return lists_.depthComplexity();
  }
  std::vector<std::string> warnings(Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;
  std::string timingEmulated() const override { return emulated_; }

 private:
  Pass resolvePass() const;
  ShaderDefines defines() const;

  Options opt_;
  ExactShadow lists_;
  Buffer params_, resolve_, count_, nodes_, status_;
  Pipeline pipeline_;
  std::string emulated_;
};

}  // namespace sb
