#include "techniques/dual_peel/dual_peel.h"

#include "render/common/composite.h"
#include "render/shading/hair_shading.h"
#include "techniques/dual_peel/slots.h"

namespace sb {

namespace {
constexpr uint32_t kDepth = SB_SLOT_DUAL_DEPTH, kFront = SB_SLOT_DUAL_FRONT,
                   kOpaque = SB_SLOT_DUAL_OPAQUE_DEPTH, kBackTemp = SB_SLOT_DUAL_BACK_TEMP,
                   kFrontFinal = SB_SLOT_DUAL_FRONT_FINAL, kBackFinal = SB_SLOT_DUAL_BACK_FINAL;
// The min/max target's clear: (-1, -1), no fragment (nearest 1 > farthest -1).
constexpr std::array<float, 4> kNoDepth = {-1.0f, -1.0f, 0.0f, 0.0f};
}  // namespace

void DualPeelOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                        const HairShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  const uint32_t w = s.width, h = s.height;
  for (int i = 0; i < 2; ++i) {
    const std::string n = std::to_string(i);
    depth_[i] = dev.createTexture({"dual_peel.depth" + n, Owner::Oit, Format::RG32F, w, h, false});
    front_[i] =
        dev.createTexture({"dual_peel.front" + n, Owner::Oit, Format::RGBA32F, w, h, false});
  }
  backTemp_ = dev.createTexture({"dual_peel.back_layer", Owner::Oit, Format::RGBA32F, w, h, false});
  back_ = dev.createTexture({"dual_peel.back", Owner::Oit, Format::RGBA32F, w, h, false});

  // The geometry passes: MAX blending on every target, no depth test (the
  // opaque depth is tested in the shader).
  const ShaderDefines hair = shading.hairDefines();
  const ShaderCode vert = Geometry::strandVertexShader(s);
  auto geometry = [&](const Pass& pass, const char* define) {
    ShaderDefines defs = hair;
    defs.defines.push_back({define, "1"});
    const ShaderCode frag = loadShader("techniques/dual_peel/peel.frag", defs);
    PipelineDesc d = pass.pipeline(dev, pass.name(), name() + "+" + shading.shadow().name());
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    d.blend.assign(d.colorFormats.size(), BlendState::max());
    return dev.createPipeline(d);
  };
  init_ = geometry(initPass(), "SB_DUAL_INIT");
  peel_ = geometry(peelPass(1), "SB_DUAL_PEEL");
  // Back layer over the back accumulation: colour a c + (1 - a) B, alpha
  // (the back transmittance) T (1 - a).
  const BlendState over{true,         BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha,
                        BlendOp::Add, BlendFactor::Zero,     BlendFactor::OneMinusSrcAlpha,
                        BlendOp::Add};
  back_blend_ = fullScreenPipeline(dev, backPass(), "dual_peel.back", name(),
                                   "techniques/dual_peel/back.frag", {}, {over});
  final_ = fullScreenPipeline(dev, finalPass(), "dual_peel.final", name(),
                              "techniques/dual_peel/final.frag", {}, {hairOverBlend()});
}

// The back accumulation (T = 1), and the opaque depth when nothing opaque was
// drawn (the geometry passes sample it).
Pass DualPeelOit::clearPass() const {
  Pass p("dual_peel.clear");
  p.color(back_, LoadOp::Clear, {0, 0, 0, 1});
  if (!targets_.opaqueDrawn) p.depth(targets_.depth, LoadOp::Clear);
  return p;
}

Pass DualPeelOit::initPass() const {
  Pass p("dual_peel.init");
  p.color(depth_[0], LoadOp::Clear, kNoDepth).color(front_[0], LoadOp::Clear);
  return p.sample(kOpaque, targets_.depth).inputs(shading_->hairInputs());
}

Pass DualPeelOit::peelPass(uint32_t pass) const {
  const uint32_t cur = pass % 2, prev = (pass + 1) % 2;
  Pass p("dual_peel.peel");
  p.color(depth_[cur], LoadOp::Clear, kNoDepth)
      .color(front_[cur], LoadOp::Clear)
      .color(backTemp_, LoadOp::Clear);
  return p.sample(kDepth, depth_[prev])
      .sample(kFront, front_[prev])
      .sample(kOpaque, targets_.depth)
      .inputs(shading_->hairInputs());
}

Pass DualPeelOit::backPass() const {
  return Pass("dual_peel.back").color(back_, LoadOp::Load).sample(kBackTemp, backTemp_);
}

Pass DualPeelOit::finalPass() const {
  return Pass("dual_peel.final")
      .colorOver(targets_.color, targets_.opaqueDrawn, settings_.background)
      .sample(kFrontFinal, front_[peelPasses() % 2])
      .sample(kBackFinal, back_);
}

void DualPeelOit::addPasses(FrameGraph& graph, Device& dev) {
  std::vector<Pass> passes = {clearPass(), initPass()};
  // Declared before prepare() counts the layers: as many as the cap allows.
  for (uint32_t i = 1; i <= std::min((maxLayers_ + 1) / 2, 2u); ++i) {
    passes.push_back(peelPass(i));
    passes.push_back(backPass());
  }
  passes.push_back(finalPass());
  graph.add(name(), passes, [this, &dev] {
    clearPass().draw(dev, Pipeline{}, 0);
    initPass().draw(dev, init_, hairVertices());
    for (uint32_t i = 1; i <= peelPasses(); ++i) {
      peelPass(i).draw(dev, peel_, hairVertices());
      backPass().draw(dev, back_blend_, 3);
    }
    finalPass().draw(dev, final_, 3);
  });
}

std::vector<Counter> DualPeelOit::counters(Device&) {
  return {{"layers", double(layers_)},
          {"peel_passes", double(peelPasses())},
          {"geometry_passes", double(peelPasses() + 1)}};
}

std::vector<std::string> DualPeelOit::warnings(Device&) {
  if (layers_ < complexity_.max)
    return {"dual depth peeling capped at " + std::to_string(layers_) + " of " +
            std::to_string(complexity_.max) + " layers (option layers=)"};
  return {};
}

}  // namespace sb
