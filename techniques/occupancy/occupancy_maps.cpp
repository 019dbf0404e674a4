#include "techniques/occupancy/occupancy_maps.h"

namespace sb {

ShaderDefines OccupancyMaps::defines() const {
  ShaderDefines d;
  d.defines.push_back({"SB_OCC_SLICES", std::to_string(config_.slices)});
  d.defines.push_back({"SB_OCC_SLABS", std::to_string(config_.slabMap ? config_.slabs : 1)});
  d.defines.push_back({"SB_OCC_WORD_TARGETS", std::to_string(wordTargets())});
  d.defines.push_back({"SB_OCC_SLAB_TARGETS", std::to_string(slabTargets())});
  return d;
}

void OccupancyMaps::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                          Buffer viewUbo, const Config& config) {
  config_ = config;
  scene_ = &scene;
  settings_ = s;
  viewUbo_ = viewUbo;
  const uint32_t w = config.width, h = config.height;
  range_ =
      dev.createTexture({config.prefix + ".depth_range", config.owner, Format::RG32F, w, h, false});
  bits_ = dev.createTexture(
      {config.prefix + ".bits", config.owner, Format::RGBA32UI, w, h, false, wordTargets()});
  if (config.slabMap)
    slabs_ = dev.createTexture(
        {config.prefix + ".slabs", config.owner, Format::RGBA32F, w, h, false, slabTargets()});
  if (!scene.hasHair()) return;  // the passes only clear the maps

  const ShaderDefines defs = defines();
  const ShaderCode vert = Geometry::strandVertexShader(s);
  PipelineDesc d;
  d.technique = config.prefix;
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.hasDepth = d.depthTest = bool(config.depth);  // hair behind the opaque mesh is left out
  d.depthCompare = CompareOp::Less;
  d.bindings = Geometry::slots();

  const ShaderCode rangeFrag = loadShader("techniques/common/depth_range.frag", defs);
  d.name = config.prefix + ".depth_range";
  d.fragment = &rangeFrag;
  d.colorFormats = {Format::RG32F};
  d.blend = {BlendState::min()};
  rangePipeline_ = dev.createPipeline(d);

  d.bindings.push_back({kRangeBinding, BindingKind::SampledTexture});
  const ShaderCode bitsFrag = loadShader("techniques/occupancy/occupancy.frag", defs);
  d.name = config.prefix + ".occupancy";
  d.fragment = &bitsFrag;
  d.colorFormats.assign(wordTargets(), Format::RGBA32UI);
  d.blend.clear();
  d.logicOpOr = true;
  bitsPipeline_ = dev.createPipeline(d);

  if (!config.slabMap) return;
  const ShaderCode slabsFrag = loadShader("techniques/occupancy/slabs.frag", defs);
  d.name = config.prefix + ".slabs";
  d.fragment = &slabsFrag;
  d.colorFormats.assign(slabTargets(), Format::RGBA32F);
  d.blend.assign(slabTargets(), BlendState::additive());
  d.logicOpOr = false;
  slabsPipeline_ = dev.createPipeline(d);
}

PassDesc OccupancyMaps::pass(const std::string& step, bool first) const {
  PassDesc p;
  p.name = config_.prefix + "." + step;
  if (config_.depth)
    p.depth = {config_.depth, first && config_.clearDepth ? LoadOp::Clear : LoadOp::Load, 1.0f};
  if (!first) p.sampledTextures = {range_};
  return p;
}

std::vector<Texture> OccupancyMaps::maps() const {
  std::vector<Texture> t = {range_, bits_};
  if (slabs_) t.push_back(slabs_);
  return t;
}

std::vector<std::string> OccupancyMaps::reads() const {
  std::vector<std::string> r = {config_.graph + "_range", config_.graph + "_bits"};
  if (config_.slabMap) r.push_back(config_.graph + "_slabs");
  return r;
}

void OccupancyMaps::addPasses(FrameGraph& graph, Device& dev) {
  // Draws the hair into the pass's targets (nothing when the scene has none).
  auto drawHair = [this, &dev](Pipeline p, bool readsRange) {
    if (!p) return;
    auto b = Geometry::bindings(*scene_, viewUbo_);
    if (readsRange) b.push_back(Binding::tex(kRangeBinding, range_));
    dev.draw(p, b, Geometry::strandVertexCount(*scene_, settings_));
  };
  // From the eye the passes test against the opaque depth (and the first clears it).
  std::vector<std::string> firstReads, mapReads = {config_.graph + "_range"};
  std::vector<std::string> firstWrites = {config_.graph + "_range"};
  if (config_.depth) {
    if (!config_.clearDepth) firstReads.push_back("depth");
    firstWrites.push_back("depth");
    mapReads.push_back("depth");
  }
  graph.add({config_.prefix + ".depth_range", firstReads, firstWrites, [this, drawHair, &dev] {
               PassDesc p = pass("depth_range", true);
               ColorAttachment a;
               a.texture = range_;
               a.clear = {2.0f, 2.0f, 0.0f, 0.0f};  // nearest 2, furthest -2: empty
               p.color = {a};
               dev.beginPass(p);
               drawHair(rangePipeline_, false);
               dev.endPass();
             }});
  graph.add(
      {config_.prefix + ".occupancy", mapReads, {config_.graph + "_bits"}, [this, drawHair, &dev] {
         PassDesc p = pass("occupancy", false);
         for (uint32_t k = 0; k < wordTargets(); ++k)
           p.color.push_back({bits_, LoadOp::Clear, {}, {}, k});
         dev.beginPass(p);
         drawHair(bitsPipeline_, true);
         dev.endPass();
       }});
  if (!config_.slabMap) return;
  graph.add(
      {config_.prefix + ".slabs", mapReads, {config_.graph + "_slabs"}, [this, drawHair, &dev] {
         PassDesc p = pass("slabs", false);
         for (uint32_t m = 0; m < slabTargets(); ++m)
           p.color.push_back({slabs_, LoadOp::Clear, {}, {}, m});
         dev.beginPass(p);
         drawHair(slabsPipeline_, true);
         dev.endPass();
       }});
}

}  // namespace sb
