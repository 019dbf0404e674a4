#include "techniques/peel_classic/peel_classic.h"

#include <cstring>

#include "render/common/composite.h"
#include "render/shading/hair_shading.h"
#include "techniques/peel_classic/slots.h"

namespace sb {

namespace {
constexpr uint32_t kPrevDepth = SB_SLOT_PEELC_PREV_DEPTH, kOpaque = SB_SLOT_PEELC_OPAQUE_DEPTH,
                   kLayerColor = SB_SLOT_PEELC_LAYER_COLOR, kLayerDepth = SB_SLOT_PEELC_LAYER_DEPTH,
                   kUnder = SB_SLOT_PEELC_UNDER;
constexpr float kNoLayer = 2.0f;  // an R32F depth no fragment has: "nothing peeled here"
}  // namespace

void ClassicPeelOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                           const HairShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  const uint32_t w = s.width, h = s.height;
  layerColor_ = dev.createTexture({"peel_classic.layer", Owner::Oit, Format::RGBA32F, w, h, false});
  for (int i = 0; i < 2; ++i)
    layerDepth_[i] = dev.createTexture(
        {"peel_classic.layer_depth" + std::to_string(i), Owner::Oit, Format::R32F, w, h, false});
  peelDepth_ = dev.createTexture({"peel_classic.depth", Owner::Oit, Format::Depth32F, w, h, false});
  under_ = dev.createTexture({"peel_classic.under", Owner::Oit, Format::RGBA32F, w, h, false});
  peeled_ = dev.createTexture({"peel_classic.peeled", Owner::Oit, Format::R32F, w, h, false});

  // The layer: colour (a c, a) and its depth, nearest by the depth test.
  const Pass lp = layerPass(0);
  {  // (HairOit::hairPipeline has no colour targets: the layer pass has two)
    const ShaderDefines hair = shading.hairDefines();
    const ShaderCode vert = Geometry::strandVertexShader(s);
    const ShaderCode frag = loadShader("techniques/peel_classic/layer.frag", hair);
    PipelineDesc d = lp.pipeline(dev, lp.name(), name() + "+" + shading.shadow().name());
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    d.depthCompare = CompareOp::Less;
    layer_ = dev.createPipeline(d);
  }
  // Under blending (front to back): acc += (1 - acc.a) * (a c, a); and +1
  // peeled fragment where the layer has one.
  const BlendState under{true,         BlendFactor::OneMinusDstAlpha, BlendFactor::One,
                         BlendOp::Add, BlendFactor::OneMinusDstAlpha, BlendFactor::One,
                         BlendOp::Add};
  blend_ =
      fullScreenPipeline(dev, blendPass(0), "peel_classic.blend", name(),
                         "techniques/peel_classic/blend.frag", {}, {under, BlendState::additive()});
  composite_ = fullScreenPipeline(dev, compositePass(), "peel_classic.composite", name(),
                                  "techniques/peel_classic/composite.frag", {}, {hairOverBlend()});
}

// Clears the accumulation, the peeled count and the "previous layer" depth
// (0: every fragment is behind it); the opaque depth too when nothing opaque
// was drawn (the layer passes sample it).
Pass ClassicPeelOit::clearPass() const {
  Pass p("peel_classic.clear");
  p.color(under_, LoadOp::Clear).color(peeled_, LoadOp::Clear);
  p.color(layerDepth_[1], LoadOp::Clear, {0, 0, 0, 0});
  if (!targets_.opaqueDrawn) p.depth(targets_.depth, LoadOp::Clear);
  return p;
}

// Layer `layer` reads the depth layer-1 wrote (ping-pong).
Pass ClassicPeelOit::layerPass(uint32_t layer) const {
  Pass p("peel_classic.layer");
  p.color(layerColor_, LoadOp::Clear)
      .color(layerDepth_[layer % 2], LoadOp::Clear, {kNoLayer, 0, 0, 0})
      .depth(peelDepth_, LoadOp::Clear)
      .sample(kPrevDepth, layerDepth_[(layer + 1) % 2])
      .sample(kOpaque, targets_.depth);
  return p.inputs(shading_->hairInputs());
}

Pass ClassicPeelOit::blendPass(uint32_t layer) const {
  return Pass("peel_classic.blend")
      .color(under_, LoadOp::Load)
      .color(peeled_, LoadOp::Load)
      .sample(kLayerColor, layerColor_)
      .sample(kLayerDepth, layerDepth_[layer % 2]);
}

Pass ClassicPeelOit::compositePass() const {
  return Pass("peel_classic.composite")
      .colorOver(targets_.color, targets_.opaqueDrawn, settings_.background)
      .sample(kUnder, under_);
}

void ClassicPeelOit::addPasses(FrameGraph& graph, Device& dev) {
  std::vector<Pass> passes = {clearPass()};
  // Declared before prepare() counts the layers: as many as the cap allows.
  for (uint32_t l = 0; l < std::min(maxLayers_, 2u); ++l) {
    passes.push_back(layerPass(l));
    passes.push_back(blendPass(l));
  }
  passes.push_back(compositePass());
  graph.add(name(), passes, [this, &dev] {
    clearPass().draw(dev, Pipeline{}, 0);
    for (uint32_t l = 0; l < layers_; ++l) {
      layerPass(l).draw(dev, layer_, hairVertices());
      blendPass(l).draw(dev, blend_, 3);
    }
    compositePass().draw(dev, composite_, 3);
  });
}

// Fragments the strict second depth test lost: every visible fragment counted
// once, less those peeled.
std::vector<Counter> ClassicPeelOit::counters(Device& dev) {
  double peeled = 0;
  const std::vector<uint8_t> bytes = dev.readTexture(peeled_);
  for (std::size_t i = 0; i + 4 <= bytes.size(); i += 4) {
    float v = 0;
    std::memcpy(&v, bytes.data() + i, 4);
    peeled += v;
  }
  const double total = double(complexity_.total);
  const bool capped = layers_ < complexity_.max;
  std::vector<Counter> out = {{"layers", double(layers_)},
                              {"geometry_passes", double(layers_)},
                              {"fragments", total},
                              {"peeled", peeled}};
  // With a cap, the fragments beyond it are not ties: count ties only uncapped.
  if (!capped) out.push_back({"lost_ties", total - peeled});
  return out;
}

std::vector<std::string> ClassicPeelOit::warnings(Device& dev) {
  std::vector<std::string> w;
  if (layers_ < complexity_.max)
    w.push_back("classic depth peeling capped at " + std::to_string(layers_) + " of " +
                std::to_string(complexity_.max) + " layers (option layers=)");
  for (const Counter& c : counters(dev))
    if (c.name == "lost_ties" && c.value > 0)
      w.push_back("classic depth peeling lost " + std::to_string(uint64_t(c.value)) +
                  " fragments at the depth of a peeled one (ties; --oit peel breaks them)");
  return w;
}

}  // namespace sb
