#include "techniques/wboit/wboit.h"

namespace sb {

BlendedOitBase::Config WeightedBlendedOit::config() const {
  Config c;
  c.accumulateShader = "techniques/wboit/accumulate.frag";
  c.resolveShader = "techniques/wboit/resolve.frag";
  c.targets.push_back({"accum",
                       precisionBits_ == 16 ? Format::RGBA16F : Format::RGBA32F,
                       BlendState::additive(),
                       {0, 0, 0, 0}});
  const BlendState revealage{true,         BlendFactor::Zero, BlendFactor::OneMinusSrcColor,
                             BlendOp::Add, BlendFactor::Zero, BlendFactor::OneMinusSrcAlpha,
                             BlendOp::Add};
  c.targets.push_back({"revealage", Format::R32F, revealage, {1, 1, 1, 1}});
  c.defines.defines.push_back({"SB_WBOIT_WEIGHT", std::to_string(weightEq_)});
  return c;
}

}  // namespace sb
