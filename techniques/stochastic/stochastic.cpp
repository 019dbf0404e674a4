#include "techniques/stochastic/stochastic.h"

#include "scenes/options.h"
#include "techniques/common/composite.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_STOCH_PARAMS, kOpaqueDepth = SB_SLOT_STOCH_OPAQUE_DEPTH,
                   kAccum = SB_SLOT_STOCH_ACCUM, kAlpha = SB_SLOT_STOCH_ALPHA;
constexpr uint32_t kMaxSamples = 64;
}  // namespace

StochasticOit::Options StochasticOit::readOptions(const OptionReader& o) {
  Options out;
  out.samples = static_cast<uint32_t>(o.integer("samples", 1, kMaxSamples));
  out.seed = static_cast<uint32_t>(o.integer("seed", 0, 4294967295LL));
  return out;
}

void StochasticOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                          const KajiyaKayShading& shading, const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
  // The largest multisample count the device has that divides S (a mask has
  // at most 32 bits); 1 always qualifies.
  perGroup_ = 1;
  for (uint32_t m = 2; m <= 32 && m <= options_.samples; m *= 2)
    if (options_.samples % m == 0 && dev.supportsSamples(m)) perGroup_ = m;
  const uint32_t m = perGroup_;

  params_.clear();
  for (uint32_t g = 0; g < groups(); ++g) {
    const uint32_t p[4] = {options_.seed, g, m, targets.opaqueDrawn ? 1u : 0u};
    params_.push_back(dev.createBuffer(
        {"stochastic.params" + std::to_string(g), "frame", BufferUsage::Uniform, sizeof p}, p));
  }
  const uint32_t w = s.width, h = s.height;
  depthMs_ = dev.createTexture({"stochastic.depth", "oit", Format::Depth32F, w, h, false, 1, m});
  accumMs_ = dev.createTexture({"stochastic.accum_ms", "oit", Format::RGBA32F, w, h, false, 1, m});
  accum_ = dev.createTexture({"stochastic.accum", "oit", Format::RGBA32F, w, h, false});
  sum_ = dev.createTexture({"stochastic.sum", "oit", Format::RGBA32F, w, h, false});
  alpha_ = dev.createTexture({"stochastic.alpha", "oit", Format::R32F, w, h, false});

  const ShaderDefines defs = shading.hairDefines();
  const ShaderCode vert = Geometry::strandVertexShader(s);
  auto hairPipeline = [&](const std::string& pass, const std::string& shader, const Pass& decl,
                          auto&& fill) {
    const ShaderCode frag = loadShader(shader, defs);
    PipelineDesc d;
    d.name = pass;
    d.technique = name() + "+" + shading.shadow().name();
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    d.bindings = decl.slots();
    fill(d);
    return dev.createPipeline(d);
  };
  // Total alpha: T *= (1 - a), one sample, against the opaque depth.
  alphaPipe_ = hairPipeline(
      "stochastic.alpha", "techniques/stochastic/alpha.frag", alphaPass(), [](PipelineDesc& d) {
        d.colorFormats = {Format::R32F};
        d.blend = {{true, BlendFactor::Zero, BlendFactor::OneMinusSrcColor, BlendOp::Add,
                    BlendFactor::Zero, BlendFactor::OneMinusSrcAlpha, BlendOp::Add}};
        d.hasDepth = d.depthTest = true;
        d.depthCompare = CompareOp::Less;
      });
  // The stochastic depth: nearest covering fragment per sample.
  depthPipe_ = hairPipeline("stochastic.depth", "techniques/stochastic/depth.frag", depthPass(0),
                            [m](PipelineDesc& d) {
                              d.hasDepth = d.depthTest = d.depthWrite = true;
                              d.depthCompare = CompareOp::Less;
                              d.samples = m;
                            });
  // Accumulation: every fragment where it is not behind the stochastic depth.
  accumulatePipe_ = hairPipeline("stochastic.accumulate", "techniques/stochastic/accumulate.frag",
                                 accumulatePass(0), [m](PipelineDesc& d) {
                                   d.colorFormats = {Format::RGBA32F};
                                   d.blend = {BlendState::additive()};
                                   d.hasDepth = d.depthTest = true;
                                   d.depthCompare = CompareOp::LessEqual;
                                   d.samples = m;
                                 });

  sumPipe_ = fullScreenPipeline(dev, "stochastic.sum", name(), "techniques/stochastic/sum.frag", {},
                                {Format::RGBA32F}, {BlendState::additive()}, sumPass(0).slots());
  resolvePipe_ =
      fullScreenPipeline(dev, "stochastic.resolve", name(), "techniques/stochastic/resolve.frag",
                         {}, {Format::RGBA32F}, {hairOverBlend()}, resolvePass().slots());
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

// The multisampled passes test the opaque depth in the shader (its one sample
// cannot be their attachment); without a mesh there is nothing to test.
Inputs StochasticOit::hairInputs(uint32_t group) const {
  Inputs in = shading_->hairInputs();
  in.uniform(kParams, params_.empty() ? Buffer{} : params_[group]);
  in.sample(kOpaqueDepth, targets_.depth);
  return in;
}

Pass StochasticOit::depthPass(uint32_t group) const {
  Pass p("stochastic.depth");
  p.depth(depthMs_, LoadOp::Clear);
  return p.inputs(hairInputs(group));
}

Pass StochasticOit::accumulatePass(uint32_t group) const {
  Pass p("stochastic.accumulate");
  p.color(accumMs_, LoadOp::Clear).resolveInto(accum_).depthReadOnly(depthMs_);
  return p.inputs(hairInputs(group));
}

Pass StochasticOit::sumPass(uint32_t group) const {
  Pass p("stochastic.sum");
  p.color(sum_, group == 0 ? LoadOp::Clear : LoadOp::Load);
  return p.sample(kAccum, accum_);
}

Pass StochasticOit::resolvePass() const {
  const glm::vec3 bg = settings_.background;
  Pass p("stochastic.resolve");
  p.color(targets_.color, targets_.opaqueDrawn ? LoadOp::Load : LoadOp::Clear,
          {bg.r, bg.g, bg.b, 1.0f});
  return p.sample(kAccum, sum_).sample(kAlpha, alpha_);
}

void StochasticOit::addPasses(FrameGraph& graph, Device& dev) {
  std::vector<Pass> passes = {alphaPass()};
  for (uint32_t g = 0; g < groups(); ++g) {
    passes.push_back(depthPass(g));
    passes.push_back(accumulatePass(g));
    passes.push_back(sumPass(g));
  }
  passes.push_back(resolvePass());
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add(name(), passes, [this, &dev, passes, vertices] {
    passes.front().draw(dev, alphaPipe_, vertices);
    for (uint32_t g = 0; g < groups(); ++g) {
      passes[1 + 3 * g].draw(dev, depthPipe_, vertices);
      passes[2 + 3 * g].draw(dev, accumulatePipe_, vertices);
      passes[3 + 3 * g].draw(dev, sumPipe_, 3);
    }
    passes.back().draw(dev, resolvePipe_, 3);
  });
}

}  // namespace sb
