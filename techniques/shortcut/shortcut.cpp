#include "techniques/shortcut/shortcut.h"

#include "render/common/hair_oit.h"
#include "render/shading/hair_shading.h"
#include "techniques/shortcut/slots.h"

namespace sb {

namespace {
constexpr uint32_t kDepths = SB_SLOT_SHORTCUT_DEPTHS, kColors = SB_SLOT_SHORTCUT_COLORS,
                   kClaims = SB_SLOT_SHORTCUT_CLAIMS, kTail = SB_SLOT_SHORTCUT_TAIL,
                   kRevealage = SB_SLOT_SHORTCUT_REVEALAGE;
}  // namespace

void ShortCutOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                        const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  const std::size_t slots = std::size_t(s.width) * s.height * std::size_t(k_);
  depths_ = dev.createBuffer({"shortcut.depths", Owner::Oit, BufferUsage::Storage, slots * 4});
  colors_ = dev.createBuffer({"shortcut.colors", Owner::Oit, BufferUsage::Storage, slots * 16});
  claims_ = dev.createBuffer({"shortcut.claims", Owner::Oit, BufferUsage::Storage, slots * 4});
  tail_ =
      dev.createTexture({"shortcut.tail", Owner::Oit, Format::RGBA32F, s.width, s.height, false});
  revealage_ =
      dev.createTexture({"shortcut.revealage", Owner::Oit, Format::R32F, s.width, s.height, false});

  ShaderDefines defs;
  defs.defines.push_back({"SB_SHORTCUT_K", std::to_string(k_)});
  ShaderDefines shaded = defs;
  shaded.add(shading.hairDefines());
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode depthsFrag = loadShader("techniques/shortcut/depths.frag", defs);
  const ShaderCode colorsFrag = loadShader("techniques/shortcut/colors.frag", shaded);

  PipelineDesc d = transparentHairDesc(dev, depthsPass(), "shortcut.depths", "shortcut", vert, s);
  d.fragment = &depthsFrag;
  // dst *= (1 - alpha): the product of (1 - alpha) over the pixel's fragments.
  d.blend = {{true, BlendFactor::Zero, BlendFactor::OneMinusSrcColor, BlendOp::Add,
              BlendFactor::Zero, BlendFactor::OneMinusSrcAlpha, BlendOp::Add}};
  depthsPipeline_ = dev.createPipeline(d);

  PipelineDesc c = transparentHairDesc(dev, colorsPass(), "shortcut.colors",
                                       "shortcut+" + shading.shadow().name(), vert, s);
  c.fragment = &colorsFrag;
  c.blend = {BlendState::additive()};
  colorsPipeline_ = dev.createPipeline(c);

  resolvePipeline_ =
      fullScreenPipeline(dev, resolvePass(), "shortcut.resolve", "shortcut",
                         "techniques/shortcut/resolve.frag", defs, {hairOverBlend()});
}

Inputs ShortCutOit::slots() const {
  Inputs in;
  in.storage(kDepths, depths_).storage(kColors, colors_).storage(kClaims, claims_);
  return in;
}

// The first pass clears the depth when nothing opaque was drawn.
Pass ShortCutOit::depthsPass() const {
  Pass p("shortcut.depths");
  p.color(revealage_, LoadOp::Clear, {1, 1, 1, 1});
  if (targets_.opaqueDrawn)
    p.depthReadOnly(targets_.depth);
  else
    p.depth(targets_.depth, LoadOp::Clear);
  return p.inputs(Geometry::inputs(*scene_, shading_->viewUbo())).inputs(slots());
}

Pass ShortCutOit::colorsPass() const {
  Pass p("shortcut.colors");
  p.color(tail_, LoadOp::Clear, {0, 0, 0, 0}).depthReadOnly(targets_.depth);
  return p.inputs(shading_->hairInputs()).inputs(slots());
}

Pass ShortCutOit::resolvePass() const {
  Pass p("shortcut.resolve");
  p.colorOver(targets_.color, targets_.opaqueDrawn, settings_.background)
      .uniform(bind::kView, shading_->viewUbo())
      .readStorage(kDepths, depths_)
      .readStorage(kColors, colors_)
      .readStorage(kClaims, claims_)
      .sample(kTail, tail_)
      .sample(kRevealage, revealage_);
  return p;
}

void ShortCutOit::addPasses(FrameGraph& graph, Device& dev) {
  const Pass depths = depthsPass(), colors = colorsPass(), resolve = resolvePass();
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add("shortcut", {depths, colors, resolve}, [this, &dev, depths, colors, resolve, vertices] {
    dev.fillBuffer(depths_, 0xFFFFFFFFu);
    dev.fillBuffer(claims_, 0u);
    depths.draw(dev, depthsPipeline_, vertices);
    colors.draw(dev, colorsPipeline_, vertices);
    resolve.draw(dev, resolvePipeline_, 3);
  });
}

}  // namespace sb
