#include "techniques/occupancy/occupancy_maps.h"

namespace sb {

ShaderDefines OccupancyMaps::defines() const {
  ShaderDefines d;
  d.defines.push_back({"SB_OCC_SLICES", std::to_string(config_.slices)});
  d.defines.push_back({"SB_OCC_SLABS", std::to_string(config_.slabMap ? config_.slabs : 1)});
  d.defines.push_back({"SB_OCC_WORD_TARGETS", std::to_string(wordTargets())});
  d.defines.push_back({"SB_OCC_SLAB_TARGETS", std::to_string(slabTargets())});
  // The arrays of occupancy_math.glsl, sized to these maps.
  d.defines.push_back({"SB_OCC_MAX_WORDS", std::to_string(maxWords())});
  d.defines.push_back({"SB_OCC_MAX_SLABS", std::to_string(maxSlabs())});
  if (config_.lightDistance) d.defines.push_back({"SB_LIGHT_DISTANCE", "1"});
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
  // Each pass's pipeline, named after it. With a depth (from the eye): tested,
  // so that hair behind the opaque mesh is left out, never written.
  auto hairDesc = [&](const Pass& pass) {
    PipelineDesc d = pass.pipeline(dev, pass.name(), config.prefix);
    d.vertex = &vert;
    d.topology = Geometry::strandTopology(s);
    d.depthWrite = false;
    d.depthCompare = CompareOp::Less;
    return d;
  };

  const ShaderCode rangeFrag = loadShader("render/common/depth_range.frag", defs);
  PipelineDesc range = hairDesc(rangePass());
  range.fragment = &rangeFrag;
  range.blend = {BlendState::min()};
  rangePipeline_ = dev.createPipeline(range);

  const ShaderCode bitsFrag = loadShader("techniques/occupancy/occupancy.frag", defs);
  PipelineDesc bits = hairDesc(bitsPass());
  bits.fragment = &bitsFrag;
  bits.logicOpOr = true;
  bitsPipeline_ = dev.createPipeline(bits);

  if (!config.slabMap) return;
  const ShaderCode slabsFrag = loadShader("techniques/occupancy/slabs.frag", defs);
  PipelineDesc slabs = hairDesc(slabsPass());
  slabs.fragment = &slabsFrag;
  slabs.blend.assign(slabTargets(), BlendState::additive());
  slabsPipeline_ = dev.createPipeline(slabs);
}

// A hair pass of the maps. From the eye the passes test against the opaque
// depth, and the first clears it when nothing opaque was drawn.
Pass OccupancyMaps::hairPass(const std::string& step, bool first) const {
  Pass p(config_.prefix + "." + step);
  if (config_.depth && first && config_.clearDepth)
    p.depth(config_.depth, LoadOp::Clear);
  else if (config_.depth)
    p.depthReadOnly(config_.depth);
  p.inputs(Geometry::inputs(*scene_, viewUbo_));
  if (!first) p.sample(kRangeBinding, range_);
  return p;
}

Pass OccupancyMaps::rangePass() const {
  return hairPass("depth_range", true)
      .color(range_, LoadOp::Clear, {2.0f, 2.0f, 0.0f, 0.0f});  // nearest 2, furthest -2: empty
}

Pass OccupancyMaps::bitsPass() const {
  Pass p = hairPass("occupancy", false);
  for (uint32_t k = 0; k < wordTargets(); ++k) p.colorUint(bits_, LoadOp::Clear, {}, k);
  return p;
}

Pass OccupancyMaps::slabsPass() const {
  Pass p = hairPass("slabs", false);
  for (uint32_t m = 0; m < slabTargets(); ++m) p.color(slabs_, LoadOp::Clear, {}, m);
  return p;
}

std::vector<Texture> OccupancyMaps::maps() const {
  std::vector<Texture> t = {range_, bits_};
  if (slabs_) t.push_back(slabs_);
  return t;
}

void OccupancyMaps::addPasses(FrameGraph& graph, Device& dev) {
  const uint32_t vertices = scene_->hasHair() ? Geometry::strandVertexCount(*scene_, settings_) : 0;
  graph.add(rangePass(),
            [this, &dev, vertices, p = rangePass()] { p.draw(dev, rangePipeline_, vertices); });
  graph.add(bitsPass(),
            [this, &dev, vertices, p = bitsPass()] { p.draw(dev, bitsPipeline_, vertices); });
  if (!config_.slabMap) return;
  graph.add(slabsPass(),
            [this, &dev, vertices, p = slabsPass()] { p.draw(dev, slabsPipeline_, vertices); });
}

}  // namespace sb
