#include "techniques/weighted/weighted.h"

#include "render/shading/hair_shading.h"

namespace sb {

namespace {
constexpr uint32_t kFirstTarget = SB_SLOT_BLENDED_TARGETS;  // resolve: sampler bindings 16, 17, ...
}  // namespace

void BlendedOitBase::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                           const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  const Config cfg = config();
  targetDescs_ = cfg.targets;
  textures_.clear();
  samplesTextures_.clear();
  // --msaa N: the hair accumulates per sample into N-sample targets, averaged into the
  // single-sampled ones the resolve reads (a per-pixel resolve of the averaged sums: exact
  // where a pixel's samples see the same fragments, as lines do here; the edges of ribbons
  // and of the mesh are where the samples differ).
  const uint32_t n = s.msaa;
  for (const Target& t : cfg.targets) {
    textures_.push_back(
        dev.createTexture({name() + "." + t.name, Owner::Oit, t.format, s.width, s.height, false}));
    if (n > 1)
      samplesTextures_.push_back(dev.createTexture(
          {name() + "." + t.name + "_ms", Owner::Oit, t.format, s.width, s.height, false, 1, n}));
  }

  // Accumulation: the hair, shaded through the shadow lookup, depth-tested
  // against the opaque depth without writing it.
  ShaderDefines defs = cfg.defines;
  defs.add(shading.hairDefines());
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader(cfg.accumulateShader, defs);
  PipelineDesc d = accumulatePass().pipeline(dev, name() + ".accumulate",
                                             name() + "+" + shading.shadow().name());
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  for (const Target& t : cfg.targets) d.blend.push_back(t.blend);
  d.depthWrite = false;  // also where the pass clears the depth (nothing opaque drawn)
  d.depthCompare = CompareOp::Less;
  accumulate_ = dev.createPipeline(d);

  // Resolve: (hair, T) over the opaque colour, C = hair + T * C_dst; the
  // destination alpha is kept.
  const ShaderCode fullScreen = loadShader("render/common/composite.vert");
  const ShaderCode resolve = loadShader(cfg.resolveShader, cfg.defines);
  // Over the (multisampled) opaque colour, then averaged into the frame.
  PipelineDesc r = resolvePass().pipeline(dev, name() + ".resolve", name());
  r.vertex = &fullScreen;
  r.fragment = &resolve;
  r.blend = {{true, BlendFactor::One, BlendFactor::SrcAlpha, BlendOp::Add, BlendFactor::Zero,
              BlendFactor::One, BlendOp::Add}};
  resolve_ = dev.createPipeline(r);
}

// Nothing opaque drawn: the accumulation, the first pass, clears the depth to 1.
Pass BlendedOitBase::accumulatePass() const {
  Pass p(name() + ".accumulate");
  for (std::size_t i = 0; i < textures_.size(); ++i) {
    if (samplesTextures_.empty()) {
      p.color(textures_[i], LoadOp::Clear, targetDescs_[i].clear);
    } else {
      p.color(samplesTextures_[i], LoadOp::Clear, targetDescs_[i].clear);
      p.resolveInto(textures_[i]);
    }
  }
  if (targets_.opaqueDrawn)
    p.depthReadOnly(targets_.depth);
  else
    p.depth(targets_.depth, LoadOp::Clear);
  return p.inputs(shading_->hairInputs());
}

Pass BlendedOitBase::resolvePass() const {
  Pass p(name() + ".resolve");
  p.colorOver(targets_.color, targets_.opaqueDrawn, settings_.background);
  if (targets_.resolved) p.resolveInto(targets_.resolved);  // --msaa: the samples averaged
  for (uint32_t i = 0; i < textures_.size(); ++i) p.sample(kFirstTarget + i, textures_[i]);
  return p;
}

void BlendedOitBase::addPasses(FrameGraph& graph, Device& dev) {
  const Pass accumulate = accumulatePass(), resolve = resolvePass();
  graph.add(name(), {accumulate, resolve}, [this, &dev, accumulate, resolve] {
    accumulate.draw(dev, accumulate_, Geometry::strandVertexCount(*scene_, settings_));
    resolve.draw(dev, resolve_, 3);
  });
}

BlendedOitBase::Config WeightedOit::config() const {
  Config c;
  c.accumulateShader = "techniques/weighted/accumulate.frag";
  c.resolveShader = "techniques/weighted/resolve.frag";
  c.targets.push_back({"accum", Format::RGBA32F, BlendState::additive(), {0, 0, 0, 0}});
  if (mode_ == Mode::Average) {
    c.targets.push_back({"count", Format::R32F, BlendState::additive(), {0, 0, 0, 0}});
    c.defines.defines.push_back({"SB_WEIGHTED_COUNT", "1"});
  }
  return c;
}

}  // namespace sb
