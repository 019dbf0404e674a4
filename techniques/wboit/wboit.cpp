#include "techniques/wboit/wboit.h"

namespace sb {

int WeightedBlendedOit::weightFromName(const std::string& name) {
  if (name == "eq7") return 7;
  if (name == "eq8") return 8;
  if (name == "eq9") return 9;
  if (name == "eq10") return 10;
  return 0;
}

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
