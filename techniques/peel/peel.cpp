#include "techniques/peel/peel.h"

#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
// As in techniques/peel/peel.frag (16 is the accumulation, 17 the counts).
constexpr uint32_t kState = SB_SLOT_PEEL_STATE, kPeeled = SB_SLOT_PEEL_PEELED;
constexpr uint32_t kSize = SB_SLOT_PEEL_ADVANCE_SIZE;  // peel_advance.comp's size uniform
}  // namespace

void PeelOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                    const KajiyaKayShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  state_ = dev.createBuffer({"peel.state", "oit", BufferUsage::Storage, pixels() * 16ull});
  peeled_ = dev.createBuffer({"peel.layers", "oit", BufferUsage::Storage, pixels() * 4ull});
  const glm::uvec4 size(pixels(), s.width, s.height, 0);
  sizeUbo_ = dev.createBuffer({"peel.size", "frame", BufferUsage::Uniform, sizeof size}, &size);
  const char* names[3] = {"peel.depth", "peel.id", "peel.shade"};
  for (int pass = 0; pass < 3; ++pass) {
    ShaderDefines defs;
    defs.defines.push_back({"SB_PEEL_PASS", std::to_string(pass)});
    step_[pass] = hairPipeline(dev, names[pass], "techniques/peel/peel.frag", defs,
                               {AccumComposite::kAccumBinding, kState, kPeeled});
  }
  advance_ = makePeelAdvancePipeline(dev, kState, kPeeled, 0, 0, "peel");
}

void PeelOit::prepare(Device& dev) {
  countFragments(dev);
  layers_ = std::min(complexity_.max, maxLayers_);
}

void PeelOit::addPasses(FrameGraph& graph, Device& dev) {
  graph.add({"peel", graphReads(), {"color"}, [this, &dev] {
               dev.fillBuffer(composite_.accum(), 0);
               dev.fillBuffer(peeled_, 0);
               dev.fillBuffer(state_, 0xFFFFFFFFu);
               auto b = shading_->hairBindings();
               b.push_back(Binding::buf(AccumComposite::kAccumBinding, composite_.accum()));
               b.push_back(Binding::buf(kState, state_));
               b.push_back(Binding::buf(kPeeled, peeled_));
               const std::vector<Binding> advance = {Binding::buf(kSize, sizeUbo_),
                                                     Binding::buf(kState, state_),
                                                     Binding::buf(kPeeled, peeled_)};
               const char* names[3] = {"peel.depth", "peel.id", "peel.shade"};
               for (uint32_t layer = 0; layer < layers_; ++layer) {
                 for (int pass = 0; pass < 3; ++pass) {
                   dev.beginPass(hairPass(names[pass], layer == 0 && pass == 0));
                   dev.draw(step_[pass], b, hairVertices());
                   dev.endPass();
                 }
                 const glm::uvec2 g = dispatchGroups(pixels());
                 dev.dispatch("peel.advance", advance_, advance, g.x, g.y);
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
