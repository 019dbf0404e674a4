// What the exact transparency techniques share: the state kept from setup(),
// hair passes depth-tested against the opaque depth, the counting pass that
// sizes them, and the accumulation they composite.
#pragma once

#include <algorithm>

#include "render/common/composite.h"
#include "render/common/fragment_lists.h"
#include "render/common/shader_library.h"
#include "render/common/technique.h"

namespace sb {

// What every transparent hair pass's pipeline shares: the strands (`vert`,
// the settings' topology), depth-tested against the opaque depth (Less)
// without writing it, so that hair behind the opaque mesh is left out; its
// targets and slots from `pass` (Pass::pipeline), which has the opaque depth
// as its depth attachment. The caller adds the fragment shader and blend.
PipelineDesc transparentHairDesc(const Device& dev, const Pass& pass, const std::string& name,
                                 const std::string& technique, const ShaderCode& vert,
                                 const RenderSettings& s);

// A transparency technique's inputs, kept from setup() for its passes.
class KeptInputsOit : public OitTechnique {
 protected:
  void keep(const GpuScene& scene, const RenderSettings& s, const HairShading& shading,
            const OitTargets& targets);

  const GpuScene* scene_ = nullptr;
  const HairShading* shading_ = nullptr;
  RenderSettings settings_;
  OitTargets targets_;
};

// A transparency technique that composites its own accumulation over the
// opaque image: the inputs it keeps from setup() and its composite.
class CompositedOit : public KeptInputsOit {
 protected:
  // Keeps the inputs and sets up the accumulation/composite.
  void keepInputs(Device& dev, const GpuScene& scene, const RenderSettings& s,
                  const HairShading& shading, const OitTargets& targets);

  AccumComposite composite_;
};

class HairOit : public CompositedOit {
 public:
  static constexpr uint32_t kCountsBinding = SB_SLOT_OIT_COUNTS;
  bool needsPrepare() const override { return true; }  // the counting pass
  std::optional<DepthComplexity> depthComplexity() const override { return complexity_; }

 protected:
  // Keeps the inputs (keepInputs), creates the per-pixel count buffer and the
  // counting pipeline.
  void setupCommon(Device& dev, const GpuScene& scene, const RenderSettings& s,
                   const HairShading& shading, const OitTargets& targets);
  // A hair pass with no colour target, depth-tested against the opaque depth
  // (cleared instead when nothing opaque was drawn and `first` is set), with
  // the shading inputs (geometry, shading, shadow lookup).
  Pass hairPass(const std::string& name, bool first) const;
  // The pipeline of a hair pass, for `fragShader`, named after the pass.
  Pipeline hairPipeline(Device& dev, const Pass& pass, const std::string& fragShader,
                        ShaderDefines defs) const;
  // Counts the visible hair fragments of every pixel (one frame).
  ListLayout countFragments(Device& dev);
  uint32_t hairVertices() const { return Geometry::strandVertexCount(*scene_, settings_); }
  uint32_t pixels() const { return settings_.width * settings_.height; }

  DepthComplexity complexity_;
  Buffer counts_;
  Pipeline count_;

 private:
  Pass countPass() const;
};

// The depth-peeling techniques: they peel as many layers as the deepest pixel
// has (counted once in prepare(), as an occlusion query per layer would stop),
// capped by the `layers` option (reported as a warning).
class PeelingOit : public HairOit {
 public:
  explicit PeelingOit(uint32_t maxLayers) : maxLayers_(maxLayers) {}
  void prepare(Device& dev) override {
    countFragments(dev);
    layers_ = std::min(complexity_.max, maxLayers_);
  }
  uint32_t layers() const { return layers_; }

 protected:
  uint32_t maxLayers_;
  uint32_t layers_ = 0;
};

}  // namespace sb
