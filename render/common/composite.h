// The accumulation buffer of the exact transparency techniques and the pass
// that puts it over the opaque result ("oit.composite").
#pragma once

#include "render/common/technique.h"

namespace sb {

// A full-screen pass's pipeline: render/common/composite.vert and
// `fragShader`, drawn with 3 vertices, its targets and slots from `pass`
// (Pass::pipeline).
Pipeline fullScreenPipeline(Device& dev, const Pass& pass, const std::string& name,
                            const std::string& technique, const std::string& fragShader,
                            const ShaderDefines& defines, std::vector<BlendState> blend);
// The blend of a resolve writing vec4(hair, T) over the opaque colour:
// C = hair + T * C_dst (One, SrcAlpha), the destination alpha kept.
inline BlendState hairOverBlend() {
  return {true,         BlendFactor::One,  BlendFactor::SrcAlpha,
          BlendOp::Add, BlendFactor::Zero, BlendFactor::One,
          BlendOp::Add};
}

class AccumComposite {
 public:
  static constexpr uint32_t kAccumBinding = SB_SLOT_OIT_ACCUM;  // vec4 per pixel, premultiplied
  void setup(Device& dev, const RenderSettings& s, Buffer viewUbo, const OitTargets& targets,
             const std::string& technique);
  Buffer accum() const { return accum_; }
  // The composite pass (clearing the target first when nothing opaque was drawn).
  Pass pass() const;
  // Records it.
  void record(Device& dev) const;

 private:
  RenderSettings settings_;
  OitTargets targets_;
  Buffer accum_, viewUbo_;
  Pipeline pipeline_;
};

}  // namespace sb
