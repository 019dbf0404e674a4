#include "techniques/occupancy/occupancy.h"

#include "base/options.h"
#include "render/common/shader_library.h"
#include "techniques/occupancy/slots.h"
#include "techniques/occupancy/uniforms.h"

namespace sb {

namespace {
// Binding numbers, as in techniques/occupancy/lookup.glsl (15: OpaqueShadow).
constexpr uint32_t kParams = SB_SLOT_OCC_PARAMS, kRange = SB_SLOT_OCC_RANGE,
                   kBits = SB_SLOT_OCC_BITS, kSlabs = SB_SLOT_OCC_SLABS;
}  // namespace

void OccupancyShadow::finish(Options& opts) {
  opts.slabMap = opts.slabMapChoice != Options::SlabMap::Off;
  opts.countOnly = opts.slabMapChoice == Options::SlabMap::Count;
  if (opts.countOnly) opts.slabs = 1;  // one count per texel: F of the paper's F / S
  const std::string what = "shadow technique 'occupancy': ";
  if (opts.slices % 32 != 0)
    throw InputError(what + "slices=" + std::to_string(opts.slices) +
                     " must be a multiple of 32 (128 per RGBA32UI target)");
  if (opts.slabMap && opts.slices % opts.slabs != 0)
    throw InputError(what + "slabs=" + std::to_string(opts.slabs) + " must divide slices=" +
                     std::to_string(opts.slices) + " (every slab holds the same number of slices)");
}

ShadowLookup OccupancyShadow::lookup() const {
  ShadowLookup l{"techniques/occupancy/lookup.glsl", maps_.defines()};
  l.defines.defines.push_back({"SB_OCC_JITTER", opts_.jitter ? "1" : "0"});
  l.defines.defines.push_back({"SB_OCC_JITTER_SAMPLES", std::to_string(opts_.jitterSamples)});
  l.inputs.uniform(kParams, params_).sample(kRange, maps_.range()).sampleArray(kBits, maps_.bits());
  if (maps_.slabs()) l.inputs.sampleArray(kSlabs, maps_.slabs());
  opaque_.addTo(l);
  return l;
}

void OccupancyShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const uint32_t size = opts_.size;
  const ViewUniforms view = lightView(s, size, size);
  lightView_ = createLightViewBuffer(dev, view, "occupancy");
  params_ = createLightLookupParams<OccupancyParams>(dev, view, opts_.bias, size, scene.shadowAlpha,
                                                     "occupancy");
  OccupancyMaps::Config c;
  c.prefix = "occupancy";
  c.owner = Owner::Shadow;
  c.width = c.height = size;
  c.slices = opts_.slices;
  c.slabs = opts_.slabs;
  c.slabMap = opts_.slabMap;
  c.lightDistance = true;
  maps_.setup(dev, scene, s, lightView_, c);
  opaque_.setup(dev, scene, size, lightView_, "occupancy");
}

void OccupancyShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  maps_.addPasses(graph, dev);
}

}  // namespace sb
