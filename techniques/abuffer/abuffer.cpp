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
}  // namespace

void ABufferOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                       const KajiyaKayShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  offsets_ = dev.createBuffer({"abuffer.offsets", "oit", BufferUsage::Storage, pixels() * 4ull});
  cursor_ = dev.createBuffer({"abuffer.cursor", "oit", BufferUsage::Storage, pixels() * 4ull});
  status_ = dev.createBuffer({"abuffer.status", "oit", BufferUsage::Storage, 16});
  const glm::uvec4 size(pixels(), s.width, s.height, 0);
  sizeUbo_ = dev.createBuffer({"abuffer.size", "frame", BufferUsage::Uniform, sizeof size}, &size);
  fill_ = hairPipeline(dev, fillPass(), "techniques/abuffer/fill.frag", {});

  const ShaderCode comp = loadShader("techniques/abuffer/resolve.comp");
  PipelineDesc c;
  c.name = "abuffer.resolve";
  c.technique = "abuffer";
  c.compute = &comp;
  c.bindings = resolvePass().slots();
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

// The lists: the fill appends to them, the resolve sorts and accumulates them.
Inputs ABufferOit::lists() const {
  Inputs in;
  in.storage(AccumComposite::kAccumBinding, composite_.accum())
      .storage(kCountsBinding, counts_)
      .storage(kOffsets, offsets_)
      .storage(kCursor, cursor_)
      .storage(kFragments, fragments_)
      .storage(kStatus, status_);
  return in;
}

Pass ABufferOit::fillPass() const { return hairPass("abuffer.fill", true).inputs(lists()); }

Pass ABufferOit::resolvePass() const {
  return Pass("abuffer.resolve").uniform(kSize, sizeUbo_).inputs(lists());
}

void ABufferOit::addPasses(FrameGraph& graph, Device& dev) {
  const Pass fill = fillPass(), resolve = resolvePass(), composite = composite_.pass();
  graph.add("abuffer", {fill, resolve, composite}, [this, &dev, fill, resolve] {
    dev.fillBuffer(cursor_, 0);
    dev.fillBuffer(status_, 0);
    fill.draw(dev, fill_, hairVertices());
    const glm::uvec2 g = dispatchGroups(pixels());
    resolve.dispatch(dev, resolve_, g.x, g.y);
    composite_.record(dev);
  });
}

std::vector<std::string> ABufferOit::warnings(Device& dev) {
  const auto status = dev.readBuffer(status_);
  if (status[0] || status[1] || status[2] || status[3])
    return {"eye-space A-buffer overflow: fragments were dropped"};
  return {};
}

}  // namespace sb
