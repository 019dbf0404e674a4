#include "techniques/occupancy_oit/occupancy_oit.h"

#include "scenes/options.h"
#include "techniques/common/shader_library.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
// The occupancy and slab shaders of the shadow version read the range at 9;
// the accumulation pass (which also binds the shadow lookup, 8..15) reads the
// maps at 20.. (techniques/occupancy_oit/accumulate.frag).
constexpr uint32_t kMapRange = 9;
constexpr uint32_t kRange = 20, kBitsFirst = 21, kSlabsFirst = 25;
constexpr uint32_t kMaxSlices = 512, kMaxSlabs = 16;

std::string indexed(const std::string& base, std::size_t i, std::size_t count) {
  return count > 1 ? base + std::to_string(i) : base;
}
}  // namespace

OccupancyOit::Options OccupancyOit::readOptions(const OptionReader& o) {
  Options opts;
  opts.slices = static_cast<uint32_t>(o.integer("slices", 32, kMaxSlices));
  opts.slabs = static_cast<uint32_t>(o.integer("slabs", 1, kMaxSlabs));
  opts.lambda = o.choice("lambda", {"on", "off"}) == "on";
  const std::string what = "transparency technique 'occupancy': ";
  if (opts.slices % 32 != 0)
    throw InputError(what + "slices=" + std::to_string(opts.slices) +
                     " must be a multiple of 32 (128 per RGBA32UI target)");
  if (opts.slices % opts.slabs != 0)
    throw InputError(what + "slabs=" + std::to_string(opts.slabs) + " must divide slices=" +
                     std::to_string(opts.slices) + " (every slab holds the same number of slices)");
  return opts;
}

PassDesc OccupancyOit::hairPass(const std::string& name, bool first) const {
  PassDesc pass;
  pass.name = name;
  pass.depth = {targets_.depth, first && !targets_.opaqueDrawn ? LoadOp::Clear : LoadOp::Load,
                1.0f};
  return pass;
}

void OccupancyOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                         const KajiyaKayShading& shading, const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
  const uint32_t w = s.width, h = s.height;
  // Every target of the technique (owner "oit"); no buffers, no uniforms.
  range_ = dev.createTexture({"occupancy_oit.depth_range", "oit", Format::RG32F, w, h, false});
  for (uint32_t k = 0; k < wordTargets(); ++k)
    bits_.push_back(dev.createTexture(
        {indexed("occupancy_oit.bits", k, wordTargets()), "oit", Format::RGBA32UI, w, h, false}));
  for (uint32_t m = 0; m < slabTargets(); ++m)
    slabs_.push_back(dev.createTexture(
        {indexed("occupancy_oit.slabs", m, slabTargets()), "oit", Format::RGBA32F, w, h, false}));
  accum_ = dev.createTexture({"occupancy_oit.accum", "oit", Format::RGBA32F, w, h, false});
  log2T_ =
      dev.createTexture({"occupancy_oit.log2_transmittance", "oit", Format::R32F, w, h, false});

  ShaderDefines defs;
  defs.defines.push_back({"SB_OCC_SLICES", std::to_string(opts_.slices)});
  defs.defines.push_back({"SB_OCC_SLABS", std::to_string(opts_.slabs)});
  defs.defines.push_back({"SB_OCC_WORD_TARGETS", std::to_string(wordTargets())});
  defs.defines.push_back({"SB_OCC_SLAB_TARGETS", std::to_string(slabTargets())});
  defs.defines.push_back({"SB_OIT_LAMBDA", opts_.lambda ? "1" : "0"});

  // The resolve: a full-screen triangle, blend One, OneMinusSrcAlpha.
  {
    const ShaderCode vert = loadShader("techniques/common/composite.vert");
    const ShaderCode frag = loadShader("techniques/occupancy_oit/resolve.frag", defs);
    PipelineDesc d;
    d.name = "occupancy_oit.resolve";
    d.technique = "occupancy_oit";
    d.vertex = &vert;
    d.fragment = &frag;
    d.colorFormats = {Format::RGBA32F};
    d.blend = {{true, BlendFactor::One, BlendFactor::OneMinusSrcAlpha, BlendOp::Add,
                BlendFactor::One, BlendFactor::OneMinusSrcAlpha, BlendOp::Add}};
    d.bindings = {{0, BindingKind::SampledTexture}, {1, BindingKind::SampledTexture}};
    resolvePipeline_ = dev.createPipeline(d);
  }
  if (!scene.hasHair()) return;  // the hair passes only clear their targets

  // The three map passes: the shadow version's shaders, from the eye.
  const ShaderCode vert = Geometry::strandVertexShader(s);
  PipelineDesc d;
  d.technique = "occupancy_oit";
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.hasDepth = d.depthTest = true;  // hair behind the opaque mesh is left out
  d.depthWrite = false;
  d.depthCompare = CompareOp::Less;
  d.bindings = Geometry::slots();

  const ShaderCode rangeFrag = loadShader("techniques/common/depth_range.frag", defs);
  d.name = "occupancy_oit.depth_range";
  d.fragment = &rangeFrag;
  d.colorFormats = {Format::RG32F};
  d.blend = {BlendState::min()};
  rangePipeline_ = dev.createPipeline(d);

  d.bindings.push_back({kMapRange, BindingKind::SampledTexture});
  const ShaderCode bitsFrag = loadShader("techniques/occupancy/occupancy.frag", defs);
  d.name = "occupancy_oit.occupancy";
  d.fragment = &bitsFrag;
  d.colorFormats.assign(wordTargets(), Format::RGBA32UI);
  d.blend.clear();
  d.logicOpOr = true;
  bitsPipeline_ = dev.createPipeline(d);

  const ShaderCode slabsFrag = loadShader("techniques/occupancy/slabs.frag", defs);
  d.name = "occupancy_oit.slabs";
  d.fragment = &slabsFrag;
  d.colorFormats.assign(slabTargets(), Format::RGBA32F);
  d.blend.assign(slabTargets(), BlendState::additive());
  d.logicOpOr = false;
  slabsPipeline_ = dev.createPipeline(d);

  // The accumulation: shaded hair (shading and shadow bindings) plus the maps.
  // Own define names: the occupancy shadow's lookup defines SB_OCC_* too.
  ShaderDefines accumDefs;
  accumDefs.defines = {{"SB_OOIT_SLICES", std::to_string(opts_.slices)},
                       {"SB_OOIT_SLABS", std::to_string(opts_.slabs)},
                       {"SB_OOIT_WORD_TARGETS", std::to_string(wordTargets())},
                       {"SB_OOIT_SLAB_TARGETS", std::to_string(slabTargets())}};
  const ShaderDefines hair = shading.hairDefines();
  for (const auto& [alias, file] : hair.aliases) accumDefs.aliases[alias] = file;
  accumDefs.defines.insert(accumDefs.defines.end(), hair.defines.begin(), hair.defines.end());
  const ShaderCode accumFrag = loadShader("techniques/occupancy_oit/accumulate.frag", accumDefs);
  d.name = "occupancy_oit.accumulate";
  d.technique = "occupancy_oit+" + shading.shadow().name();
  d.fragment = &accumFrag;
  d.colorFormats = {Format::RGBA32F, Format::R32F};
  d.blend.assign(2, BlendState::additive());
  d.bindings = shading.hairSlots();
  d.bindings.push_back({kRange, BindingKind::SampledTexture});
  for (uint32_t k = 0; k < wordTargets(); ++k)
    d.bindings.push_back({kBitsFirst + k, BindingKind::SampledTexture});
  for (uint32_t m = 0; m < slabTargets(); ++m)
    d.bindings.push_back({kSlabsFirst + m, BindingKind::SampledTexture});
  accumPipeline_ = dev.createPipeline(d);
}

void OccupancyOit::addPasses(FrameGraph& graph, Device& dev) {
  const uint32_t vertices = scene_->hasHair() ? Geometry::strandVertexCount(*scene_, settings_) : 0;
  // The map passes draw the hair with the view and scene bindings only.
  auto drawMap = [this, &dev, vertices](Pipeline p, bool readsRange) {
    if (!p) return;
    auto b = Geometry::bindings(*scene_, shading_->viewUbo());
    if (readsRange) b.push_back(Binding::tex(kMapRange, range_));
    dev.draw(p, b, vertices);
  };
  std::vector<std::string> depthReads;
  if (targets_.opaqueDrawn) depthReads.push_back("depth");

  graph.add(
      {"occupancy_oit.depth_range", depthReads, {"oit.occ_range", "depth"}, [this, &dev, drawMap] {
         PassDesc pass = hairPass("occupancy_oit.depth_range", true);
         ColorAttachment a;
         a.texture = range_;
         a.clear = {2.0f, 2.0f, 0.0f, 0.0f};  // nearest 2, furthest -2: empty
         pass.color = {a};
         dev.beginPass(pass);
         drawMap(rangePipeline_, false);
         dev.endPass();
       }});
  graph.add({"occupancy_oit.occupancy",
             {"oit.occ_range", "depth"},
             {"oit.occ_bits"},
             [this, &dev, drawMap] {
               PassDesc pass = hairPass("occupancy_oit.occupancy", false);
               for (Texture t : bits_) pass.color.push_back({t, LoadOp::Clear, {}, {}});
               pass.sampledTextures = {range_};
               dev.beginPass(pass);
               drawMap(bitsPipeline_, true);
               dev.endPass();
             }});
  graph.add(
      {"occupancy_oit.slabs", {"oit.occ_range", "depth"}, {"oit.occ_slabs"}, [this, &dev, drawMap] {
         PassDesc pass = hairPass("occupancy_oit.slabs", false);
         for (Texture t : slabs_) pass.color.push_back({t, LoadOp::Clear, {}, {}});
         pass.sampledTextures = {range_};
         dev.beginPass(pass);
         drawMap(slabsPipeline_, true);
         dev.endPass();
       }});
  auto accumReads = shading_->shadowReads();
  accumReads.insert(accumReads.end(), {"oit.occ_range", "oit.occ_bits", "oit.occ_slabs", "depth"});
  graph.add({"occupancy_oit.accumulate", accumReads, {"oit.occ_accum"}, [this, &dev, vertices] {
               PassDesc pass = hairPass("occupancy_oit.accumulate", false);
               pass.color = {{accum_, LoadOp::Clear, {}, {}}, {log2T_, LoadOp::Clear, {}, {}}};
               pass.sampledTextures = shading_->sampledTextures();
               pass.sampledTextures.push_back(range_);
               pass.sampledTextures.insert(pass.sampledTextures.end(), bits_.begin(), bits_.end());
               pass.sampledTextures.insert(pass.sampledTextures.end(), slabs_.begin(),
                                           slabs_.end());
               dev.beginPass(pass);
               if (accumPipeline_) {
                 auto b = shading_->hairBindings();
                 b.push_back(Binding::tex(kRange, range_));
                 for (uint32_t k = 0; k < bits_.size(); ++k)
                   b.push_back(Binding::tex(kBitsFirst + k, bits_[k]));
                 for (uint32_t m = 0; m < slabs_.size(); ++m)
                   b.push_back(Binding::tex(kSlabsFirst + m, slabs_[m]));
                 dev.draw(accumPipeline_, b, vertices);
               }
               dev.endPass();
             }});
  std::vector<std::string> resolveReads = {"oit.occ_accum"};
  if (targets_.opaqueDrawn) resolveReads.push_back("color");
  graph.add({"occupancy_oit.resolve", resolveReads, {"color"}, [this, &dev] {
               PassDesc pass;
               pass.name = "occupancy_oit.resolve";
               const glm::vec3 bg = settings_.background;
               pass.color = {{targets_.color,
                              targets_.opaqueDrawn ? LoadOp::Load : LoadOp::Clear,
                              {bg.r, bg.g, bg.b, 1.0f}}};
               pass.sampledTextures = {accum_, log2T_};
               dev.beginPass(pass);
               dev.draw(resolvePipeline_, {Binding::tex(0, accum_), Binding::tex(1, log2T_)}, 3);
               dev.endPass();
             }});
}

}  // namespace sb
