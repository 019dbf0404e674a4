// Single-pass blended transparency approximations: every visible hair fragment
// is accumulated with additive (or multiplicative) blending into a few
// full-screen targets, then one full-screen resolve pass blends the result over
// the opaque colour (blend One, SrcAlpha: C = hair + T * C_dst).
//   wsum: weighted sum (Meshkin 2007; Bavoil & Myers 2008)
//   wavg: weighted average (Bavoil & Myers 2008)
// techniques/wboit builds weighted blended OIT (McGuire & Bavoil 2013) on the
// same base. Hair behind the opaque mesh is rejected by the opaque depth (test
// Less, no write). Targets are owner "oit" and are the only resources made.
#pragma once

#include <array>

#include "render/common/hair_oit.h"
#include "render/common/shader_library.h"
#include "render/common/technique.h"

namespace sb {

class BlendedOitBase : public KeptInputsOit {
 public:
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;

 protected:
  struct Target {
    std::string name;  // "<technique>.<name>"
    Format format;
    BlendState blend;
    std::array<float, 4> clear;
  };
  struct Config {
    std::vector<Target> targets;   // sampled by the resolve at bindings 16, 17, ...
    std::string accumulateShader;  // hair fragment shader, one output per target
    std::string resolveShader;     // full-screen fragment shader writing (hair, T)
    ShaderDefines defines;         // for both shaders
  };
  virtual Config config() const = 0;

 private:
  Pass accumulatePass() const;
  Pass resolvePass() const;

  std::vector<Target> targetDescs_;
  std::vector<Texture> textures_;         // what the resolve reads
  std::vector<Texture> samplesTextures_;  // --msaa N > 1: the N-sample accumulation targets
  Pipeline accumulate_, resolve_;
};

// wsum and wavg (option-free).
class WeightedOit : public BlendedOitBase {
 public:
  enum class Mode { Sum, Average };
  explicit WeightedOit(Mode mode) : mode_(mode) {}
  std::string name() const override { return mode_ == Mode::Sum ? "wsum" : "wavg"; }

 protected:
  Config config() const override;

 private:
  Mode mode_;
};

}  // namespace sb
