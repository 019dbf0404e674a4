#include "techniques/peel/peel.h"

#include "techniques/common/shader_library.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
constexpr uint32_t kState = 17, kPeeled = 18, kCounts = 19;
}

void PeelOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                    const KajiyaKayShading& shading, const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
  const std::size_t pixels = std::size_t(s.width) * s.height;
  composite_.setup(dev, s, shading.viewUbo(), targets, "peel");
  state_ = dev.createBuffer({"peel.state", "oit", BufferUsage::Storage, pixels * 16});
  peeled_ = dev.createBuffer({"peel.layers", "oit", BufferUsage::Storage, pixels * 4});
  counts_ = dev.createBuffer({"peel.counts", "oit", BufferUsage::Storage, pixels * 4});
  const glm::uvec4 size(uint32_t(pixels), s.width, s.height, 0);
  sizeUbo_ = dev.createBuffer({"peel.size", "oit", BufferUsage::Uniform, sizeof size}, &size);

  count_ = makeHairCountPipeline(dev, s, kCounts, true, "peel");
  const ShaderCode vert = Geometry::strandVertexShader(s);
  PipelineDesc d;
  d.technique = "peel+" + shading.shadow().name();
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.hasDepth = d.depthTest = true;  // hair behind the opaque mesh is left out
  d.depthCompare = CompareOp::Less;
  d.bindings = shading.hairSlots();
  for (uint32_t b : {AccumComposite::kAccumBinding, kState, kPeeled})
    d.bindings.push_back({b, BindingKind::StorageBuffer});
  for (int pass = 0; pass < 3; ++pass) {
    ShaderDefines defs = shading.hairDefines();
    defs.defines.push_back({"SB_PEEL_PASS", std::to_string(pass)});
    const ShaderCode frag = loadShader("techniques/peel/peel.frag", defs);
    d.name = pass == 0 ? "peel.depth" : pass == 1 ? "peel.id" : "peel.shade";
    d.fragment = &frag;
    step_[pass] = dev.createPipeline(d);
  }
  advance_ = makePeelAdvancePipeline(dev, kState, kPeeled, 0, 0, "peel");
}

PassDesc PeelOit::hairPass(const std::string& name, bool first) const {
  PassDesc pass;
  pass.name = name;
  // Without a mesh nothing wrote the depth: the first pass of a frame clears it.
  pass.depth = {targets_.depth, first && !targets_.opaqueDrawn ? LoadOp::Clear : LoadOp::Load,
                1.0f};
  pass.sampledTextures = shading_->sampledTextures();
  return pass;
}

void PeelOit::prepare(Device& dev) {
  dev.fillBuffer(counts_, 0);
  dev.beginFrame();
  dev.beginPass(hairPass("peel.count", true));
  auto b = Geometry::bindings(*scene_, shading_->viewUbo());
  b.push_back(Binding::buf(kCounts, counts_));
  dev.draw(count_, b, Geometry::strandVertexCount(*scene_, settings_));
  dev.endPass();
  dev.endFrame();
  complexity_ = layoutFromCounts(dev.readBuffer(counts_)).complexity;
  layers_ = std::min(complexity_.max, maxLayers_);
}

void PeelOit::addPasses(FrameGraph& graph, Device& dev) {
  auto reads = shading_->shadowReads();
  reads.push_back("depth");
  if (targets_.opaqueDrawn) reads.push_back("color");
  graph.add({"peel", reads, {"color"}, [this, &dev] {
               dev.fillBuffer(composite_.accum(), 0);
               dev.fillBuffer(peeled_, 0);
               dev.fillBuffer(state_, 0xFFFFFFFFu);
               auto b = shading_->hairBindings();
               b.push_back(Binding::buf(AccumComposite::kAccumBinding, composite_.accum()));
               b.push_back(Binding::buf(kState, state_));
               b.push_back(Binding::buf(kPeeled, peeled_));
               const std::vector<Binding> advance = {Binding::buf(0, sizeUbo_),
                                                     Binding::buf(kState, state_),
                                                     Binding::buf(kPeeled, peeled_)};
               const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
               const uint32_t pixels = settings_.width * settings_.height;
               const char* names[3] = {"peel.depth", "peel.id", "peel.shade"};
               for (uint32_t layer = 0; layer < layers_; ++layer) {
                 for (int pass = 0; pass < 3; ++pass) {
                   dev.beginPass(hairPass(names[pass], layer == 0 && pass == 0));
                   dev.draw(step_[pass], b, vertices);
                   dev.endPass();
                 }
                 dev.dispatch("peel.advance", advance_, advance, (pixels + 63) / 64);
               }
               if (layers_ == 0 && !targets_.opaqueDrawn) {  // still clear the depth
                 dev.beginPass(hairPass("peel.depth", true));
                 dev.endPass();
               }
               composite_.record(dev);
             }});
}

std::vector<std::string> PeelOit::warnings(Device&) {
  if (layers_ < complexity_.max)
    return {"depth peeling capped at " + std::to_string(layers_) + " of " +
            std::to_string(complexity_.max) + " layers (option layers=)"};
  return {};
}

}  // namespace sb
