#include "techniques/abuffer/abuffer.h"

#include "techniques/common/shader_library.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
// As in techniques/abuffer/abuffer.glsl.
constexpr uint32_t kCounts = 17, kOffsets = 18, kCursor = 19, kFragments = 20, kStatus = 21;
constexpr std::size_t kFragmentBytes = 32;
}  // namespace

void ABufferOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                       const KajiyaKayShading& shading, const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
  const std::size_t pixels = std::size_t(s.width) * s.height;
  composite_.setup(dev, s, shading.viewUbo(), targets, "abuffer");
  counts_ = dev.createBuffer({"abuffer.counts", "oit", BufferUsage::Storage, pixels * 4});
  offsets_ = dev.createBuffer({"abuffer.offsets", "oit", BufferUsage::Storage, pixels * 4});
  cursor_ = dev.createBuffer({"abuffer.cursor", "oit", BufferUsage::Storage, pixels * 4});
  status_ = dev.createBuffer({"abuffer.status", "oit", BufferUsage::Storage, 16});
  const glm::uvec4 size(uint32_t(pixels), s.width, s.height, 0);
  sizeUbo_ = dev.createBuffer({"abuffer.size", "oit", BufferUsage::Uniform, sizeof size}, &size);

  count_ = makeHairCountPipeline(dev, s, kCounts, true, "abuffer");
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("techniques/abuffer/fill.frag", shading.hairDefines());
  PipelineDesc d;
  d.name = "abuffer.fill";
  d.technique = "abuffer+" + shading.shadow().name();
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.hasDepth = d.depthTest = true;  // hair behind the opaque mesh is left out
  d.depthCompare = CompareOp::Less;
  d.bindings = shading.hairSlots();
  for (uint32_t b :
       {AccumComposite::kAccumBinding, kCounts, kOffsets, kCursor, kFragments, kStatus})
    d.bindings.push_back({b, BindingKind::StorageBuffer});
  fill_ = dev.createPipeline(d);

  const ShaderCode comp = loadShader("techniques/abuffer/resolve.comp");
  PipelineDesc c;
  c.name = "abuffer.resolve";
  c.technique = "abuffer";
  c.compute = &comp;
  c.bindings = {{0, BindingKind::UniformBuffer}};
  for (uint32_t b :
       {AccumComposite::kAccumBinding, kCounts, kOffsets, kCursor, kFragments, kStatus})
    c.bindings.push_back({b, BindingKind::StorageBuffer});
  resolve_ = dev.createPipeline(c);
}

PassDesc ABufferOit::hairPass(const std::string& name) const {
  PassDesc pass;
  pass.name = name;
  pass.depth = {targets_.depth, targets_.opaqueDrawn ? LoadOp::Load : LoadOp::Clear, 1.0f};
  pass.sampledTextures = shading_->sampledTextures();
  return pass;
}

void ABufferOit::prepare(Device& dev) {
  dev.fillBuffer(counts_, 0);
  dev.beginFrame();
  dev.beginPass(hairPass("abuffer.count"));
  auto b = Geometry::bindings(*scene_, shading_->viewUbo());
  b.push_back(Binding::buf(kCounts, counts_));
  dev.draw(count_, b, Geometry::strandVertexCount(*scene_, settings_));
  dev.endPass();
  dev.endFrame();
  const ListLayout layout = layoutFromCounts(dev.readBuffer(counts_));
  complexity_ = layout.complexity;
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

void ABufferOit::addPasses(FrameGraph& graph, Device& dev) {
  auto reads = shading_->shadowReads();
  reads.push_back("depth");
  if (targets_.opaqueDrawn) reads.push_back("color");
  graph.add({"abuffer", reads, {"color"}, [this, &dev] {
               dev.fillBuffer(cursor_, 0);
               dev.fillBuffer(status_, 0);
               const std::vector<Binding> lists = {
                   Binding::buf(AccumComposite::kAccumBinding, composite_.accum()),
                   Binding::buf(kCounts, counts_),
                   Binding::buf(kOffsets, offsets_),
                   Binding::buf(kCursor, cursor_),
                   Binding::buf(kFragments, fragments_),
                   Binding::buf(kStatus, status_)};
               auto b = shading_->hairBindings();
               b.insert(b.end(), lists.begin(), lists.end());
               dev.beginPass(hairPass("abuffer.fill"));
               dev.draw(fill_, b, Geometry::strandVertexCount(*scene_, settings_));
               dev.endPass();
               auto r = lists;
               r.push_back(Binding::buf(0, sizeUbo_));
               const uint32_t pixels = settings_.width * settings_.height;
               dev.dispatch("abuffer.resolve", resolve_, r, (pixels + 63) / 64);
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
