#include "techniques/occupancy/occupancy.h"

#include "scenes/options.h"
#include "techniques/common/shader_library.h"

namespace sb {

namespace {
// Binding numbers, as in techniques/occupancy/lookup.glsl (15: OpaqueShadow).
constexpr uint32_t kParams = 8, kRange = 9, kBitsFirst = 10;
constexpr uint32_t kMaxSlices = 512, kMaxSlabs = 16, kMaxTextures = 5;  // bindings 10..14

std::string indexed(const std::string& base, std::size_t i, std::size_t count) {
  return count > 1 ? base + std::to_string(i) : base;
}
}  // namespace

OccupancyShadow::Options OccupancyShadow::readOptions(const OptionReader& o) {
  Options opts;
  opts.size = static_cast<uint32_t>(o.integer("size", 1, 16384));
  opts.bias = static_cast<float>(o.number("bias", 0.0, 1.0));
  opts.slices = static_cast<uint32_t>(o.integer("slices", 32, kMaxSlices));
  opts.slabs = static_cast<uint32_t>(o.integer("slabs", 1, kMaxSlabs));
  opts.slabMap = o.choice("slab_map", {"on", "off"}) == "on";
  opts.jitter = o.choice("jitter", {"on", "off"}) == "on";
  const std::string what = "shadow technique 'occupancy': ";
  if (opts.slices % 32 != 0)
    throw InputError(what + "slices=" + std::to_string(opts.slices) +
                     " must be a multiple of 32 (128 per RGBA32UI target)");
  if (opts.slabMap && opts.slices % opts.slabs != 0)
    throw InputError(what + "slabs=" + std::to_string(opts.slabs) + " must divide slices=" +
                     std::to_string(opts.slices) + " (every slab holds the same number of slices)");
  const uint32_t textures = (opts.slices + 127) / 128 + (opts.slabMap ? (opts.slabs + 3) / 4 : 0);
  if (textures > kMaxTextures)
    throw InputError(what + "slices=" + std::to_string(opts.slices) + " and slabs=" +
                     std::to_string(opts.slabs) + " need " + std::to_string(textures) +
                     " textures; at most " + std::to_string(kMaxTextures) +
                     " fit the shadow bindings (ceil(slices/128) + ceil(slabs/4))");
  return opts;
}

ShaderDefines OccupancyShadow::lookupDefines() const {
  ShaderDefines d;
  d.defines.push_back({"SB_OCC_SLICES", std::to_string(opts_.slices)});
  d.defines.push_back({"SB_OCC_SLABS", std::to_string(opts_.slabMap ? opts_.slabs : 1)});
  d.defines.push_back({"SB_OCC_WORD_TARGETS", std::to_string(wordTargets())});
  d.defines.push_back({"SB_OCC_SLAB_TARGETS", std::to_string(slabTargets())});
  for (uint32_t m = 0; m < slabTargets(); ++m)
    d.defines.push_back({"SB_OCC_SLAB_BINDING" + std::to_string(m),
                         std::to_string(kBitsFirst + wordTargets() + m)});
  d.defines.push_back({"SB_OCC_JITTER", opts_.jitter ? "1" : "0"});
  opaque_.addDefines(d);
  return d;
}

void OccupancyShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  scene_ = &scene;
  settings_ = s;
  const uint32_t size = opts_.size;
  const ViewUniforms view = lightView(s, size, size);
  lightView_ = createLightViewBuffer(dev, view, "occupancy");
  params_ = createLightLookupParams(dev, view, opts_.bias, size, scene.shadowAlpha, "occupancy");
  range_ = dev.createTexture({"occupancy.depth_range", "shadow", Format::RG32F, size, size, false});
  for (uint32_t k = 0; k < wordTargets(); ++k)
    bits_.push_back(dev.createTexture({indexed("occupancy.bits", k, wordTargets()), "shadow",
                                       Format::RGBA32UI, size, size, false}));
  for (uint32_t m = 0; m < slabTargets(); ++m)
    slabs_.push_back(dev.createTexture({indexed("occupancy.slabs", m, slabTargets()), "shadow",
                                        Format::RGBA32F, size, size, false}));
  opaque_.setup(dev, scene, size, lightView_, "occupancy");
  if (!scene.hasHair()) return;  // the passes only clear the maps

  const ShaderDefines defs = lookupDefines();
  const ShaderCode vert = Geometry::strandVertexShader(s);
  PipelineDesc d;
  d.technique = "occupancy";
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.bindings = Geometry::slots();

  const ShaderCode rangeFrag = loadShader("techniques/common/depth_range.frag", defs);
  d.name = "occupancy.depth_range";
  d.fragment = &rangeFrag;
  d.colorFormats = {Format::RG32F};
  d.blend = {BlendState::min()};
  rangePipeline_ = dev.createPipeline(d);

  d.bindings.push_back({kRange, BindingKind::SampledTexture});
  const ShaderCode bitsFrag = loadShader("techniques/occupancy/occupancy.frag", defs);
  d.name = "occupancy.occupancy";
  d.fragment = &bitsFrag;
  d.colorFormats.assign(wordTargets(), Format::RGBA32UI);
  d.blend.clear();
  d.logicOpOr = true;
  bitsPipeline_ = dev.createPipeline(d);

  if (opts_.slabMap) {
    const ShaderCode slabsFrag = loadShader("techniques/occupancy/slabs.frag", defs);
    d.name = "occupancy.slabs";
    d.fragment = &slabsFrag;
    d.colorFormats.assign(slabTargets(), Format::RGBA32F);
    d.blend.assign(slabTargets(), BlendState::additive());
    d.logicOpOr = false;
    slabsPipeline_ = dev.createPipeline(d);
  }
}

void OccupancyShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  // Draws the hair into the pass's targets (nothing when the scene has none).
  auto drawHair = [this, &dev](Pipeline p, bool readsRange) {
    if (!p) return;
    auto b = Geometry::bindings(*scene_, lightView_);
    if (readsRange) b.push_back(Binding::tex(kRange, range_));
    dev.draw(p, b, Geometry::strandVertexCount(*scene_, settings_));
  };
  graph.add({"occupancy.depth_range", {}, {"shadow.occupancy_range"}, [this, &dev, drawHair] {
               PassDesc pass;
               pass.name = "occupancy.depth_range";
               ColorAttachment a;
               a.texture = range_;
               a.clear = {2.0f, 2.0f, 0.0f, 0.0f};  // nearest 2, furthest -2: empty
               pass.color = {a};
               dev.beginPass(pass);
               drawHair(rangePipeline_, false);
               dev.endPass();
             }});
  graph.add({"occupancy.occupancy",
             {"shadow.occupancy_range"},
             {"shadow.occupancy_bits"},
             [this, &dev, drawHair] {
               PassDesc pass;
               pass.name = "occupancy.occupancy";
               for (Texture t : bits_) pass.color.push_back({t, LoadOp::Clear, {}, {}});
               pass.sampledTextures = {range_};
               dev.beginPass(pass);
               drawHair(bitsPipeline_, true);
               dev.endPass();
             }});
  if (!opts_.slabMap) return;
  graph.add({"occupancy.slabs",
             {"shadow.occupancy_range"},
             {"shadow.occupancy_slabs"},
             [this, &dev, drawHair] {
               PassDesc pass;
               pass.name = "occupancy.slabs";
               for (Texture t : slabs_) pass.color.push_back({t, LoadOp::Clear, {}, {}});
               pass.sampledTextures = {range_};
               dev.beginPass(pass);
               drawHair(slabsPipeline_, true);
               dev.endPass();
             }});
}

std::vector<std::string> OccupancyShadow::lookupReads() const {
  std::vector<std::string> r = {"shadow.occupancy_range", "shadow.occupancy_bits"};
  if (opts_.slabMap) r.push_back("shadow.occupancy_slabs");
  opaque_.addReads(r);
  return r;
}

std::vector<BindingSlot> OccupancyShadow::lookupSlots() const {
  std::vector<BindingSlot> s = {{kParams, BindingKind::UniformBuffer},
                                {kRange, BindingKind::SampledTexture}};
  for (uint32_t i = 0; i < wordTargets() + slabTargets(); ++i)
    s.push_back({kBitsFirst + i, BindingKind::SampledTexture});
  opaque_.addSlots(s);
  return s;
}

std::vector<Binding> OccupancyShadow::lookupBindings() const {
  std::vector<Binding> b = {Binding::buf(kParams, params_), Binding::tex(kRange, range_)};
  uint32_t next = kBitsFirst;
  for (Texture t : bits_) b.push_back(Binding::tex(next++, t));
  for (Texture t : slabs_) b.push_back(Binding::tex(next++, t));
  opaque_.addBindings(b);
  return b;
}

std::vector<Texture> OccupancyShadow::lookupTextures() const {
  std::vector<Texture> t = {range_};
  t.insert(t.end(), bits_.begin(), bits_.end());
  t.insert(t.end(), slabs_.begin(), slabs_.end());
  opaque_.addTextures(t);
  return t;
}

}  // namespace sb
