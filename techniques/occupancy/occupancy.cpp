#include "techniques/occupancy/occupancy.h"

#include "scenes/options.h"
#include "techniques/common/shader_library.h"

namespace sb {

namespace {
// Binding numbers, as in techniques/occupancy/lookup.glsl (15: OpaqueShadow).
constexpr uint32_t kParams = 8, kRange = 9, kBits = 10, kSlabs = 11;
}  // namespace

OccupancyShadow::Options OccupancyShadow::readOptions(const OptionReader& o) {
  Options opts;
  opts.size = static_cast<uint32_t>(o.integer("size", 1, 16384));
  opts.bias = static_cast<float>(o.number("bias", 0.0, 1.0));
  opts.slices = static_cast<uint32_t>(o.integer("slices", 32, OccupancyMaps::kMaxSlices));
  opts.slabs = static_cast<uint32_t>(o.integer("slabs", 1, OccupancyMaps::kMaxSlabs));
  opts.slabMap = o.choice("slab_map", {"on", "off"}) == "on";
  opts.jitter = o.choice("jitter", {"on", "off"}) == "on";
  const std::string what = "shadow technique 'occupancy': ";
  if (opts.slices % 32 != 0)
    throw InputError(what + "slices=" + std::to_string(opts.slices) +
                     " must be a multiple of 32 (128 per RGBA32UI target)");
  if (opts.slabMap && opts.slices % opts.slabs != 0)
    throw InputError(what + "slabs=" + std::to_string(opts.slabs) + " must divide slices=" +
                     std::to_string(opts.slices) + " (every slab holds the same number of slices)");
  return opts;
}

ShaderDefines OccupancyShadow::lookupDefines() const {
  ShaderDefines d = maps_.defines();
  d.defines.push_back({"SB_OCC_JITTER", opts_.jitter ? "1" : "0"});
  opaque_.addDefines(d);
  return d;
}

void OccupancyShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const uint32_t size = opts_.size;
  const ViewUniforms view = lightView(s, size, size);
  lightView_ = createLightViewBuffer(dev, view, "occupancy");
  params_ = createLightLookupParams(dev, view, opts_.bias, size, scene.shadowAlpha, "occupancy");
  OccupancyMaps::Config c;
  c.prefix = "occupancy";
  c.owner = "shadow";
  c.graph = "shadow.occupancy";
  c.width = c.height = size;
  c.slices = opts_.slices;
  c.slabs = opts_.slabs;
  c.slabMap = opts_.slabMap;
  maps_.setup(dev, scene, s, lightView_, c);
  opaque_.setup(dev, scene, size, lightView_, "occupancy");
}

void OccupancyShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  maps_.addPasses(graph, dev);
}

std::vector<std::string> OccupancyShadow::lookupReads() const {
  std::vector<std::string> r = maps_.reads();
  opaque_.addReads(r);
  return r;
}

std::vector<BindingSlot> OccupancyShadow::lookupSlots() const {
  std::vector<BindingSlot> s = {{kParams, BindingKind::UniformBuffer},
                                {kRange, BindingKind::SampledTexture},
                                {kBits, BindingKind::SampledTextureArray}};
  if (maps_.slabs()) s.push_back({kSlabs, BindingKind::SampledTextureArray});
  opaque_.addSlots(s);
  return s;
}

std::vector<Binding> OccupancyShadow::lookupBindings() const {
  std::vector<Binding> b = {Binding::buf(kParams, params_), Binding::tex(kRange, maps_.range()),
                            Binding::tex(kBits, maps_.bits())};
  if (maps_.slabs()) b.push_back(Binding::tex(kSlabs, maps_.slabs()));
  opaque_.addBindings(b);
  return b;
}

std::vector<Texture> OccupancyShadow::lookupTextures() const {
  std::vector<Texture> t = maps_.maps();
  opaque_.addTextures(t);
  return t;
}

}  // namespace sb
