#include "techniques/stochastic/stochastic.h"

#include "base/options.h"
#include "render/common/composite.h"
#include "render/shading/hair_shading.h"
#include "techniques/stochastic/slots.h"
#include "techniques/stochastic/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_STOCH_PARAMS, kDepths = SB_SLOT_STOCH_DEPTHS,
                   kAccum = SB_SLOT_STOCH_ACCUM, kAlpha = SB_SLOT_STOCH_ALPHA;
}  // namespace

void StochasticOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                          const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  const StochasticParams p{glm::uvec4(options_.seed, options_.samples, 0, 0)};
  params_ =
      dev.createBuffer({"stochastic.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  const uint32_t w = s.width, h = s.height;
  depths_ = dev.createBuffer({"stochastic.depths", Owner::Oit, BufferUsage::Storage,
                              std::size_t(w) * h * options_.samples * 4});
  accum_ = dev.createTexture({"stochastic.accum", Owner::Oit, Format::RGBA32F, w, h, false});
  alpha_ = dev.createTexture({"stochastic.alpha", Owner::Oit, Format::R32F, w, h, false});

  const ShaderDefines defs = shading.hairDefines();
  const ShaderCode vert = Geometry::strandVertexShader(s);
  // Every hair pass tests the opaque depth (Less, no write).
  auto hairPipeline = [&](const std::string& pass, const std::string& shader, const Pass& decl,
                          auto&& fill) {
    const ShaderCode frag = loadShader(shader, defs);
    PipelineDesc d = decl.pipeline(dev, pass, name() + "+" + shading.shadow().name());
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    d.depthWrite = false;  // also where the first pass clears the depth
    d.depthCompare = CompareOp::Less;
    fill(d);
    return dev.createPipeline(d);
  };
  // Total alpha: T *= (1 - a).
  alphaPipe_ = hairPipeline(
      "stochastic.alpha", "techniques/stochastic/alpha.frag", alphaPass(), [](PipelineDesc& d) {
        d.blend = {{true, BlendFactor::Zero, BlendFactor::OneMinusSrcColor, BlendOp::Add,
                    BlendFactor::Zero, BlendFactor::OneMinusSrcAlpha, BlendOp::Add}};
      });
  // The stochastic depth: the nearest covering fragment per sample (storage only).
  depthPipe_ = hairPipeline("stochastic.depth", "techniques/stochastic/depth.frag", depthPass(),
                            [](PipelineDesc&) {});
  // Accumulation: every fragment weighted by the samples it is not behind.
  accumulatePipe_ =
      hairPipeline("stochastic.accumulate", "techniques/stochastic/accumulate.frag",
                   accumulatePass(), [](PipelineDesc& d) { d.blend = {BlendState::additive()}; });
  resolvePipe_ = fullScreenPipeline(dev, resolvePass(), "stochastic.resolve", name(),
                                    "techniques/stochastic/resolve.frag", {}, {hairOverBlend()});
}

// The first pass: it clears the depth when nothing opaque was drawn.
Pass StochasticOit::alphaPass() const {
  Pass p("stochastic.alpha");
  p.color(alpha_, LoadOp::Clear, {1, 1, 1, 1});
  if (targets_.opaqueDrawn)
    p.depthReadOnly(targets_.depth);
  else
    p.depth(targets_.depth, LoadOp::Clear);
  return p.inputs(shading_->hairInputs());
}

Pass StochasticOit::depthPass() const {
  Pass p("stochastic.depth");
  p.depthReadOnly(targets_.depth);
  return p.inputs(Geometry::inputs(*scene_, shading_->viewUbo()))
      .uniform(kParams, params_)
      .storage(kDepths, depths_);
}

Pass StochasticOit::accumulatePass() const {
  Pass p("stochastic.accumulate");
  p.color(accum_, LoadOp::Clear).depthReadOnly(targets_.depth);
  return p.inputs(shading_->hairInputs()).uniform(kParams, params_).readStorage(kDepths, depths_);
}

Pass StochasticOit::resolvePass() const {
  Pass p("stochastic.resolve");
  p.colorOver(targets_.color, targets_.opaqueDrawn, settings_.background);
  return p.sample(kAccum, accum_).sample(kAlpha, alpha_);
}

void StochasticOit::addPasses(FrameGraph& graph, Device& dev) {
  const Pass alpha = alphaPass(), depth = depthPass(), accumulate = accumulatePass(),
             resolve = resolvePass();
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add(name(), {alpha, depth, accumulate, resolve},
            [this, &dev, alpha, depth, accumulate, resolve, vertices] {
              dev.fillBuffer(depths_, 0xFFFFFFFFu);  // every sample empty (beyond depth 1)
              alpha.draw(dev, alphaPipe_, vertices);
              depth.draw(dev, depthPipe_, vertices);
              accumulate.draw(dev, accumulatePipe_, vertices);
              resolve.draw(dev, resolvePipe_, 3);
            });
}

}  // namespace sb
