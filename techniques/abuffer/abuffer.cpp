#include "techniques/abuffer/abuffer.h"

#include "techniques/common/shader_library.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
// As in techniques/abuffer/abuffer.glsl (16 is the accumulation, 17 the counts).
constexpr uint32_t kOffsets = SB_SLOT_ABUFFER_OFFSETS, kCursor = SB_SLOT_ABUFFER_CURSOR,
                   kFragments = SB_SLOT_ABUFFER_FRAGMENTS, kStatus = SB_SLOT_ABUFFER_STATUS;
constexpr uint32_t kSize = SB_SLOT_ABUFFER_SIZE;  // the resolve's size uniform
constexpr std::size_t kFragmentBytes = 32;
const std::vector<uint32_t> kLists = {
    AccumComposite::kAccumBinding, HairOit::kCountsBinding, kOffsets, kCursor, kFragments, kStatus};
}  // namespace

void ABufferOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                       const KajiyaKayShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  offsets_ = dev.createBuffer({"abuffer.offsets", "oit", BufferUsage::Storage, pixels() * 4ull});
  cursor_ = dev.createBuffer({"abuffer.cursor", "oit", BufferUsage::Storage, pixels() * 4ull});
  status_ = dev.createBuffer({"abuffer.status", "oit", BufferUsage::Storage, 16});
  const glm::uvec4 size(pixels(), s.width, s.height, 0);
  sizeUbo_ = dev.createBuffer({"abuffer.size", "frame", BufferUsage::Uniform, sizeof size}, &size);
  fill_ = hairPipeline(dev, "abuffer.fill", "techniques/abuffer/fill.frag", {}, kLists);

  const ShaderCode comp = loadShader("techniques/abuffer/resolve.comp");
  PipelineDesc c;
  c.name = "abuffer.resolve";
  c.technique = "abuffer";
  c.compute = &comp;
  c.bindings = {{kSize, BindingKind::UniformBuffer}};
  for (uint32_t b : kLists) c.bindings.push_back({b, BindingKind::StorageBuffer});
  resolve_ = dev.createPipeline(c);
}

void ABufferOit::prepare(Device& dev) {
  const ListLayout layout = countFragments(dev);
  if (complexity_.total > maxFragments_)
    throw InputError(
        "A-buffer: the scene has " + std::to_string(complexity_.total) +
        " visible hair fragments, over the limit max_fragments=" + std::to_string(maxFragments_) +
        " (" + std::to_string(complexity_.total * kFragmentBytes >> 20) +
        " MiB); lower the resolution or raise the limit");
  dev.updateBuffer(offsets_, layout.offsets.data(), layout.offsets.size() * 4);
  fragments_ = dev.createBuffer({"abuffer.fragments", "oit", BufferUsage::Storage,
                                 std::max<uint64_t>(complexity_.total, 1) * kFragmentBytes});
}

std::vector<Binding> ABufferOit::listBindings() const {
  return {Binding::buf(AccumComposite::kAccumBinding, composite_.accum()),
          Binding::buf(kCountsBinding, counts_),
          Binding::buf(kOffsets, offsets_),
          Binding::buf(kCursor, cursor_),
          Binding::buf(kFragments, fragments_),
          Binding::buf(kStatus, status_)};
}

void ABufferOit::addPasses(FrameGraph& graph, Device& dev) {
  graph.add({"abuffer", graphReads(), {"color"}, [this, &dev] {
               dev.fillBuffer(cursor_, 0);
               dev.fillBuffer(status_, 0);
               auto b = shading_->hairBindings();
               for (const auto& x : listBindings()) b.push_back(x);
               dev.beginPass(hairPass("abuffer.fill", true));
               dev.draw(fill_, b, hairVertices());
               dev.endPass();
               auto r = listBindings();
               r.push_back(Binding::buf(kSize, sizeUbo_));
               const glm::uvec2 g = dispatchGroups(pixels());
               dev.dispatch("abuffer.resolve", resolve_, r, g.x, g.y);
               composite_.record(dev);
             }});
}

std::vector<std::string> ABufferOit::warnings(Device& dev) {
  const auto status = dev.readBuffer(status_);
  if (status[0] || status[1] || status[2] || status[3])
    return {"eye-space A-buffer overflow: fragments were dropped"};
  return {};
}

}  // namespace sb
