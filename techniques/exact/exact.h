#pragma once

#include "base/options.h"
#include "render/common/fragment_lists.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Exact self-shadowing, the shadow ground truth: every light texel keeps the
// sorted depths of all hair fragments in it, and a point's visibility is
// (1 - alpha_s)^n for the n fragments in front of it. Built two independent
// ways that must agree: depth peeling from the light (method=peel: one layer
// per step, ties broken by primitive id) and a light-space A-buffer sorted per
// texel (method=abuffer). The mesh casts a hard shadow (OpaqueShadow).
class ExactShadow : public ShadowTechnique {
 public:
  enum class Method { Peel, ABuffer };
  struct Options {
    Method method;
    uint32_t size;
    float bias;
    uint32_t layers;
    bool jitter = false;         // the lookup jittered as occupancy's (a jittered reference)
    uint32_t jitterSamples = 1;  // jittered lookups averaged (jitter=on)
  };
  // Its options, declared once (unit.cpp), and those of a spec of it (InputError when one
  // is bad): the references read its map's size and bias through them (harness/).
  static const OptionTable<Options>& options();
  static Options optionsOf(const Spec& spec);
  ExactShadow(Method method, uint32_t size, float bias, uint32_t maxLayers);
  std::string name() const override { return "exact"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void prepare(Device& dev) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::optional<DepthComplexity> depthComplexity() const override { return complexity_; }

  // After a frame: per texel, the number of fragments stored and their keys
  // (for checking the two methods against each other), and problems seen.
  struct Lists {
    std::vector<uint32_t> stored;
    std::vector<uint32_t> keys;  // (depth bits, primitive id) pairs
  };
  Lists readLists(Device& dev);
  std::vector<std::string> warnings(Device& dev) override;
  // The sorted lists after addPasses' node, read only at their slots (counts,
  // offsets, cursor, nodes): what a technique built on them reads (dsm).
  Inputs sortedLists() const;
  // After setup: the defines of a shader that reads the nodes (nodes.glsl) and
  // is compiled before prepare() counts them (the lookup, dsm's, avsm's): every
  // page bound.
  ShaderDefines readerDefines() const { return pageDefines(kPages); }
  // Before setup: sort each texel's list in submission order (primitive id,
  // then depth) instead of depth order, the order ordered fragment-shader
  // interlock would process the fragments in (avsm's streaming resolve). The
  // technique's own lookup is then not the exact visibility: only for lists
  // another technique reads.
  void sortBySubmission() { bySubmission_ = true; }
  // Before setup: the lookup jittered by up to half a texel, `samples` jittered lookups
  // averaged (render/common/light_jitter.glsl, as occupancy's jitter=on); 0: not jittered.
  void jitterLookup(uint32_t samples) { jitterSamples_ = samples; }
  // For a technique built on these lists (dsm, avsm), after addPasses():
  // records `pass`, a compute pass with one invocation per texel that reads
  // sortedLists(), its `status` buffer cleared first.
  void addTexelPass(FrameGraph& graph, Device& dev, const Pass& pass, Pipeline pipeline,
                    Buffer status) const;

 private:
  Inputs lists() const;
  Inputs pages(bool written) const;
  ShaderDefines pageDefines(uint32_t pages) const;
  void makeListPipelines(Device& dev);
  Pass listPass(const std::string& name) const;
  Pass countPass() const;
  Pass sortPass() const;
  Pass advancePass() const;

  Method method_;
  uint32_t size_;
  float bias_;
  uint32_t maxLayers_;
  uint32_t layers_ = 0;
  bool bySubmission_ = false;
  uint32_t jitterSamples_ = 0;
  const GpuScene* scene_ = nullptr;
  RenderSettings settings_;
  DepthComplexity complexity_;
  Buffer params_, lightView_, counts_, offsets_, cursor_, state_, status_, sizeUbo_;
  // The node pool's pages (poolPageShift, nodes.glsl): the first is
  // "exact.nodes"; the others hold 8 bytes until a pool larger than one binding
  // needs them (the exact reference of a large anti-aliased image).
  static constexpr uint32_t kPages = 3;
  std::vector<Buffer> nodes_;
  uint32_t pageShift_ = 0, pagesUsed_ = 1;
  OpaqueShadow opaque_;
  Pipeline count_, fill_, sort_, peel0_, peel1_, advance_;
};

}  // namespace sb
