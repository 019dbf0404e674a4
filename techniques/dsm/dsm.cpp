#include "techniques/dsm/dsm.h"

#include "render/common/readback.h"
#include "render/common/shader_library.h"
#include "techniques/dsm/compress_uniforms.h"
#include "techniques/dsm/slots.h"
#include "techniques/dsm/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_DSM_PARAMS, kKept = SB_SLOT_DSM_KEPT,
                   kOffsets = SB_SLOT_DSM_OFFSETS, kNodes = SB_SLOT_DSM_NODES,
                   kOutKept = SB_SLOT_DSM_OUT_KEPT, kOutOffsets = SB_SLOT_DSM_OUT_OFFSETS,
                   kOutNodes = SB_SLOT_DSM_OUT_NODES, kOutStatus = SB_SLOT_DSM_OUT_STATUS,
                   kCompress = SB_SLOT_DSM_COMPRESS;

}  // namespace

// The lists: every fragment kept (no layer cap), sorted per texel.
DeepShadowMaps::DeepShadowMaps(const Options& o)
    : opt_(o), lists_(ExactShadow::Method::ABuffer, o.size, o.bias, 1000000) {}

void DeepShadowMaps::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  lists_.setup(dev, scene, s);
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  params_ = createLightLookupParams<DsmLookupParams>(dev, view, opt_.bias, opt_.size,
                                                     scene.shadowAlpha, "dsm");
  const DsmCompressParams c{
      glm::vec4(opt_.epsilon, 1.0f - scene.shadowAlpha, float(opt_.size), float(opt_.maxNodes))};
  compress_ = dev.createBuffer({"dsm.compress", Owner::Frame, BufferUsage::Uniform, sizeof c}, &c);
  const std::size_t texels = std::size_t(opt_.size) * opt_.size;
  kept_ = dev.createBuffer({"dsm.kept", Owner::Shadow, BufferUsage::Storage, texels * 4});
  offsets_ = dev.createBuffer({"dsm.offsets", Owner::Shadow, BufferUsage::Storage, texels * 4});
  status_ = dev.createBuffer({"dsm.status", Owner::Shadow, BufferUsage::Storage, 16});
  nodes_ = dev.createBuffer(
      {"dsm.nodes", Owner::Shadow, BufferUsage::Storage, 8});  // sized by prepare()

  const ShaderCode comp = loadShader("techniques/dsm/compress.comp", lists_.readerDefines());
  PipelineDesc c2 = compressPass().pipeline(dev, "dsm.compress", "dsm");
  c2.compute = &comp;
  pipeline_ = dev.createPipeline(c2);
}

// The node slots: min(2 n, max nodes) per texel, from the counts the lists'
// counting pass measured (the same scene every frame).
void DeepShadowMaps::prepare(Device& dev) {
  lists_.prepare(dev);
  complexity_ = lists_.depthComplexity().value_or(DepthComplexity{});
  const std::vector<uint32_t>& counts = complexity_.counts;
  std::vector<uint32_t> offsets(counts.size());
  uint64_t total = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (total > 0xFFFFFFFFull)
      throw InputError("shadow technique 'dsm': more than 2^32 nodes; lower size or max_nodes");
    offsets[i] = static_cast<uint32_t>(total);
    total += std::min<uint64_t>(2ull * counts[i], opt_.maxNodes);
  }
  dev.updateBuffer(offsets_, offsets.data(), offsets.size() * 4);
  capacity_ = std::max<uint64_t>(total, 1);
  dev.setBufferSize(nodes_, capacity_ * 8);
}

Pass DeepShadowMaps::compressPass() const {
  return Pass("dsm.compress")
      .inputs(lists_.sortedLists())
      .uniform(kCompress, compress_)
      .storage(kOutKept, kept_)
      .readStorage(kOutOffsets, offsets_)
      .storage(kOutNodes, nodes_)
      .storage(kOutStatus, status_);
}

void DeepShadowMaps::addPasses(FrameGraph& graph, Device& dev) {
  lists_.addPasses(graph, dev);
  opaque_.addPass(graph, dev);
  lists_.addTexelPass(graph, dev, compressPass(), pipeline_, status_);
}

ShadowLookup DeepShadowMaps::lookup() const {
  ShadowLookup l{"techniques/dsm/lookup.glsl"};
  l.inputs.uniform(kParams, params_)
      .readStorage(kKept, kept_)
      .readStorage(kOffsets, offsets_)
      .readStorage(kNodes, nodes_);
  opaque_.addTo(l);
  return l;
}

std::vector<uint32_t> DeepShadowMaps::keptNodes(Device& dev) {
  return readBufferAs<uint32_t>(dev, kept_);
}

std::vector<std::string> DeepShadowMaps::warnings(Device& dev) {
  std::vector<std::string> w = lists_.warnings(dev);
  const uint32_t cut = readBufferAs<uint32_t>(dev, status_)[0];
  if (cut)
    w.push_back("dsm: " + std::to_string(cut) +
                " texels needed more than max_nodes=" + std::to_string(opt_.maxNodes) +
                " nodes; their curves are cut (error above epsilon behind the cut)");
  return w;
}

// Nodes kept per texel with hair (min / mean / max) and their bytes: the
// paper's memory, beside the slots allocated.
std::vector<Counter> DeepShadowMaps::counters(Device& dev) {
  const std::vector<uint32_t> kept = keptNodes(dev);
  const std::vector<uint32_t>& counts = complexity_.counts;
  uint64_t total = 0, covered = 0;
  uint32_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < kept.size() && i < counts.size(); ++i) {
    if (!counts[i]) continue;
    lo = covered ? std::min(lo, kept[i]) : kept[i];
    hi = std::max(hi, kept[i]);
    total += kept[i];
    ++covered;
  }
  return {{"dsm_nodes_min", double(lo)},
          {"dsm_nodes_mean", covered ? double(total) / double(covered) : 0.0},
          {"dsm_nodes_max", double(hi)},
          {"dsm_nodes_total", double(total)},
          {"dsm_kept_bytes", double(total * 8)},
          {"dsm_slot_bytes", double(capacity_ * 8)}};
}

}  // namespace sb
