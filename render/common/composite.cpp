#include "render/common/composite.h"

#include "render/common/shader_library.h"

namespace sb {

Pipeline fullScreenPipeline(Device& dev, const Pass& pass, const std::string& name,
                            const std::string& technique, const std::string& fragShader,
                            const ShaderDefines& defines, std::vector<BlendState> blend) {
  const ShaderCode vert = loadShader("render/common/composite.vert");
  const ShaderCode frag = loadShader(fragShader, defines);
  PipelineDesc d = pass.pipeline(dev, name, technique);
  d.vertex = &vert;
  d.fragment = &frag;
  d.blend = std::move(blend);
  return dev.createPipeline(d);
}

void AccumComposite::setup(Device& dev, const RenderSettings& s, Buffer viewUbo,
                           const OitTargets& targets, const std::string& technique) {
  settings_ = s;
  targets_ = targets;
  viewUbo_ = viewUbo;
  accum_ = dev.createBuffer({technique + ".accum", Owner::Oit, BufferUsage::Storage,
                             std::size_t(s.width) * s.height * 16});
  const ShaderCode vert = loadShader("render/common/composite.vert");
  const ShaderCode frag = loadShader("render/common/composite.frag");
  PipelineDesc d = pass().pipeline(dev, technique + ".composite", technique);
  d.vertex = &vert;
  d.fragment = &frag;
  d.blend = {{true, BlendFactor::One, BlendFactor::OneMinusSrcAlpha, BlendOp::Add, BlendFactor::One,
              BlendFactor::OneMinusSrcAlpha, BlendOp::Add}};
  pipeline_ = dev.createPipeline(d);
}

Pass AccumComposite::pass() const {
  return Pass("oit.composite")
      .colorOver(targets_.color, targets_.opaqueDrawn, settings_.background)
      .uniform(bind::kView, viewUbo_)
      .readStorage(kAccumBinding, accum_);
}

void AccumComposite::record(Device& dev) const { pass().draw(dev, pipeline_, 3); }

}  // namespace sb
