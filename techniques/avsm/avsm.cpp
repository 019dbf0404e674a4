#include "techniques/avsm/avsm.h"

#include <cstring>

#include "render/common/shader_library.h"
#include "techniques/avsm/resolve_uniforms.h"
#include "techniques/avsm/slots.h"
#include "techniques/avsm/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_AVSM_PARAMS, kCount = SB_SLOT_AVSM_COUNT,
                   kNodes = SB_SLOT_AVSM_NODES, kOutCount = SB_SLOT_AVSM_OUT_COUNT,
                   kOutNodes = SB_SLOT_AVSM_OUT_NODES, kOutStatus = SB_SLOT_AVSM_OUT_STATUS,
                   kResolve = SB_SLOT_AVSM_RESOLVE;
}  // namespace

// The lists: every fragment kept (no layer cap), in submission order.
AdaptiveVolumetricShadowMaps::AdaptiveVolumetricShadowMaps(const Options& o)
    : opt_(o), lists_(ExactShadow::Method::ABuffer, o.size, o.bias, 1000000) {
  lists_.sortBySubmission();
}

ShaderDefines AdaptiveVolumetricShadowMaps::defines() const {
  ShaderDefines d;
  d.defines.push_back({"SB_AVSM_NODES", std::to_string(opt_.nodes)});
  return d;
}

void AdaptiveVolumetricShadowMaps::setup(Device& dev, const GpuScene& scene,
                                         const RenderSettings& s) {
  lists_.setup(dev, scene, s);
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  params_ = createLightLookupParams<AvsmLookupParams>(dev, view, opt_.bias, opt_.size,
                                                      scene.shadowAlpha, "avsm");
  const AvsmResolve r{glm::vec4(1.0f - scene.shadowAlpha, float(opt_.size), 0.0f, 0.0f)};
  resolve_ = dev.createBuffer({"avsm.resolve", Owner::Frame, BufferUsage::Uniform, sizeof r}, &r);
  const std::size_t texels = std::size_t(opt_.size) * opt_.size;
  count_ = dev.createBuffer({"avsm.count", Owner::Shadow, BufferUsage::Storage, texels * 4});
  nodes_ = dev.createBuffer({"avsm.nodes", Owner::Shadow, BufferUsage::Storage,
                             texels * (opt_.nodes + 2) * sizeof(glm::vec2)});
  status_ = dev.createBuffer({"avsm.status", Owner::Shadow, BufferUsage::Storage, 16});
  // No interlock path is written (it could not run here): with or without the
  // extension the curves are built in the resolve, in primitive order.
  emulated_ = std::string(
                  "avsm streams fragments into its curves in a resolve pass, in "
                  "primitive order (device ") +
              (dev.info().fragmentShaderInterlock
                   ? "has fragment-shader interlock; the interlock path is not written)"
                   : "has no fragment-shader interlock)");

  const ShaderCode comp =
      loadShader("techniques/avsm/resolve.comp", defines().add(lists_.readerDefines()));
  PipelineDesc c = resolvePass().pipeline(dev, "avsm.resolve", "avsm");
  c.compute = &comp;
  pipeline_ = dev.createPipeline(c);
}

void AdaptiveVolumetricShadowMaps::prepare(Device& dev) { lists_.prepare(dev); }

Pass AdaptiveVolumetricShadowMaps::resolvePass() const {
  return Pass("avsm.resolve")
      .inputs(lists_.sortedLists())
      .uniform(kResolve, resolve_)
      .storage(kOutCount, count_)
      .storage(kOutNodes, nodes_)
      .storage(kOutStatus, status_);
}

void AdaptiveVolumetricShadowMaps::addPasses(FrameGraph& graph, Device& dev) {
  lists_.addPasses(graph, dev);
  opaque_.addPass(graph, dev);
  lists_.addTexelPass(graph, dev, resolvePass(), pipeline_, status_);
}

ShadowLookup AdaptiveVolumetricShadowMaps::lookup() const {
  ShadowLookup l{"techniques/avsm/lookup.glsl"};
  l.defines.add(defines());
  l.inputs.uniform(kParams, params_).readStorage(kCount, count_).readStorage(kNodes, nodes_);
  opaque_.addTo(l);
  return l;
}

std::vector<std::string> AdaptiveVolumetricShadowMaps::warnings(Device& dev) {
  return lists_.warnings(dev);
}

// Nodes per texel with hair (mean, max), the fragments streamed (the emulated
// steps) and the nodes the compression removed; the paper's memory (counts
// and node slots) beside the lists the emulation keeps.
std::vector<Counter> AdaptiveVolumetricShadowMaps::counters(Device& dev) {
  auto uints = [&](Buffer b) {
    const std::vector<uint8_t> bytes = dev.readBuffer(b);
    std::vector<uint32_t> v(bytes.size() / 4);
    std::memcpy(v.data(), bytes.data(), v.size() * 4);
    return v;
  };
  const std::vector<uint32_t> count = uints(count_), status = uints(status_);
  uint64_t total = 0, covered = 0;
  uint32_t hi = 0;
  for (uint32_t c : count) {
    if (!c) continue;
    total += c;
    hi = std::max(hi, c);
    ++covered;
  }
  const double texels = double(opt_.size) * opt_.size;
  const DepthComplexity lists = lists_.depthComplexity().value_or(DepthComplexity{});
  return {{"avsm_nodes_mean", covered ? double(total) / double(covered) : 0.0},
          {"avsm_nodes_max", double(hi)},
          {"avsm_map_bytes", texels * (4.0 + 8.0 * opt_.nodes)},
          {"avsm_list_bytes", double(lists.total) * 8.0 + texels * 12.0},
          {"emulated_steps", double(status[0])},
          {"avsm_nodes_removed", double(status[1])}};
}

}  // namespace sb
