#include "techniques/occupancy_oit/occupancy_oit.h"

#include <algorithm>

#include "base/options.h"
#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"
#include "techniques/occupancy_oit/slots.h"

namespace sb {

namespace {
// The accumulation pass also binds the shadow lookup (8..15); the resolve
// binds only the sums.
constexpr uint32_t kRange = SB_SLOT_OOIT_RANGE, kBits = SB_SLOT_OOIT_BITS,
                   kSlabs = SB_SLOT_OOIT_SLABS;
constexpr uint32_t kResolveAccum = SB_SLOT_OOIT_ACCUM, kResolveLog2T = SB_SLOT_OOIT_LOG2T;
}  // namespace

void OccupancyOit::check(Options& opts) {
  const std::string what = "transparency technique 'occupancy': ";
  if (opts.slices % 32 != 0)
    throw InputError(what + "slices=" + std::to_string(opts.slices) +
                     " must be a multiple of 32 (128 per RGBA32UI target)");
  if (opts.slices % opts.slabs != 0)
    throw InputError(what + "slabs=" + std::to_string(opts.slabs) + " must divide slices=" +
                     std::to_string(opts.slices) + " (every slab holds the same number of slices)");
}

void OccupancyOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                         const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  const uint32_t w = s.width, h = s.height;
  // Every target of the technique (owner Oit); no buffers, no uniforms.
  OccupancyMaps::Config c;
  c.prefix = "occupancy_oit";
  c.owner = Owner::Oit;
  c.width = w;
  c.height = h;
  c.slices = opts_.slices;
  c.slabs = opts_.slabs;
  c.depth = targets.depth;
  c.clearDepth = !targets.opaqueDrawn;
  maps_.setup(dev, scene, s, shading.viewUbo(), c);
  accum_ = dev.createTexture({"occupancy_oit.accum", Owner::Oit, Format::RGBA32F, w, h, false});
  log2T_ = dev.createTexture(
      {"occupancy_oit.log2_transmittance", Owner::Oit, Format::R32F, w, h, false});

  ShaderDefines defs = maps_.defines();
  // order=printed takes Lambda as printed too (hair.a / Lambda).
  defs.defines.push_back({"SB_OIT_LAMBDA", !opts_.lambda ? "0" : opts_.order == 2 ? "2" : "1"});

  // The resolve: a full-screen triangle, blend One, OneMinusSrcAlpha.
  {
    const ShaderCode vert = loadShader("render/common/composite.vert");
    const ShaderCode frag = loadShader("techniques/occupancy_oit/resolve.frag", defs);
    PipelineDesc d = resolvePass().pipeline(dev, "occupancy_oit.resolve", "occupancy_oit");
    d.vertex = &vert;
    d.fragment = &frag;
    d.blend = {{true, BlendFactor::One, BlendFactor::OneMinusSrcAlpha, BlendOp::Add,
                BlendFactor::One, BlendFactor::OneMinusSrcAlpha, BlendOp::Add}};
    resolvePipeline_ = dev.createPipeline(d);
  }
  if (!scene.hasHair()) return;  // the hair passes only clear their targets

  // The accumulation pass draws the hair with the shading's pipeline state.
  const ShaderCode vert = Geometry::strandVertexShader(s);

  // The accumulation: shaded hair (shading and shadow bindings) plus the maps.
  // Own define names: the occupancy shadow's lookup defines SB_OCC_* too.
  ShaderDefines accumDefs;
  accumDefs.defines = {{"SB_OOIT_SLICES", std::to_string(opts_.slices)},
                       {"SB_OOIT_SLABS", std::to_string(opts_.slabs)},
                       {"SB_OOIT_WORD_TARGETS", std::to_string(maps_.wordTargets())},
                       {"SB_OOIT_SLAB_TARGETS", std::to_string(maps_.slabTargets())},
                       {"SB_OOIT_ORDER", std::to_string(opts_.order)}};
  const ShaderDefines hair = shading.hairDefines();
  for (const auto& [alias, file] : hair.aliases) accumDefs.aliases[alias] = file;
  // One size for occupancy_math.glsl's arrays, which the occupancy shadow's
  // lookup may size too: the larger of the two.
  uint32_t words = maps_.maxWords(), slabs = maps_.maxSlabs();
  for (const auto& [name, value] : hair.defines) {
    if (name == "SB_OCC_MAX_WORDS")
      words = std::max<uint32_t>(words, std::stoul(value));
    else if (name == "SB_OCC_MAX_SLABS")
      slabs = std::max<uint32_t>(slabs, std::stoul(value));
    else
      accumDefs.defines.push_back({name, value});
  }
  accumDefs.defines.push_back({"SB_OCC_MAX_WORDS", std::to_string(words)});
  accumDefs.defines.push_back({"SB_OCC_MAX_SLABS", std::to_string(slabs)});
  const ShaderCode accumFrag = loadShader("techniques/occupancy_oit/accumulate.frag", accumDefs);
  // Depth-tested (hair behind the opaque mesh is left out), not written.
  PipelineDesc d = accumulatePass().pipeline(dev, "occupancy_oit.accumulate",
                                             "occupancy_oit+" + shading.shadow().name());
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.depthCompare = CompareOp::Less;
  d.fragment = &accumFrag;
  d.blend.assign(2, BlendState::additive());
  accumPipeline_ = dev.createPipeline(d);
}

// Shaded hair weighted by its occupancy-ordered transmittance, summed; the
// depth range pass has cleared the depth when nothing opaque was drawn.
Pass OccupancyOit::accumulatePass() const {
  Pass p("occupancy_oit.accumulate");
  p.depthReadOnly(targets_.depth)
      .color(accum_, LoadOp::Clear)
      .color(log2T_, LoadOp::Clear)
      .inputs(shading_->hairInputs())
      .sample(kRange, maps_.range())
      .sampleArray(kBits, maps_.bits())
      .sampleArray(kSlabs, maps_.slabs());
  return p;
}

// The sum over the opaque result (or the background).
Pass OccupancyOit::resolvePass() const {
  return Pass("occupancy_oit.resolve")
      .colorOver(targets_.color, targets_.opaqueDrawn, settings_.background)
      .sample(kResolveAccum, accum_)
      .sample(kResolveLog2T, log2T_);
}

void OccupancyOit::addPasses(FrameGraph& graph, Device& dev) {
  const uint32_t vertices = scene_->hasHair() ? Geometry::strandVertexCount(*scene_, settings_) : 0;
  maps_.addPasses(graph, dev);
  graph.add(accumulatePass(), [this, &dev, vertices, p = accumulatePass()] {
    p.draw(dev, accumPipeline_, vertices);
  });
  graph.add(resolvePass(), [this, &dev, p = resolvePass()] { p.draw(dev, resolvePipeline_, 3); });
}

}  // namespace sb
