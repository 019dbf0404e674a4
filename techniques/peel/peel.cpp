#include "techniques/peel/peel.h"

#include "render/common/peel_uniforms.h"
#include "render/shading/hair_shading.h"

namespace sb {

namespace {
// As in techniques/peel/peel.frag (16 is the accumulation, 17 the counts).
constexpr uint32_t kState = SB_SLOT_PEEL_STATE, kPeeled = SB_SLOT_PEEL_PEELED;
constexpr uint32_t kSize = SB_SLOT_PEEL_ADVANCE_SIZE;  // peel_advance.comp's size uniform
}  // namespace

void PeelOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                    const HairShading& shading, const OitTargets& targets) {
  setupCommon(dev, scene, s, shading, targets);
  state_ = dev.createBuffer({"peel.state", Owner::Oit, BufferUsage::Storage, pixels() * 16ull});
  peeled_ = dev.createBuffer({"peel.layers", Owner::Oit, BufferUsage::Storage, pixels() * 4ull});
  const PeelSize size{glm::uvec4(pixels(), s.width, s.height, 0)};
  sizeUbo_ =
      dev.createBuffer({"peel.size", Owner::Frame, BufferUsage::Uniform, sizeof size}, &size);
  for (int step = 0; step < 3; ++step) {
    ShaderDefines defs;
    defs.defines.push_back({"SB_PEEL_PASS", std::to_string(step)});
    step_[step] = hairPipeline(dev, stepPass(step, false), "techniques/peel/peel.frag", defs);
  }
  advance_ = makePeelAdvancePipeline(dev, advancePass(), kState, kPeeled, 0, 0, "peel");
}

// One of a layer's three hair draws: smallest depth, smallest primitive id at
// that depth, shade and accumulate.
Pass PeelOit::stepPass(int step, bool first) const {
  const char* names[3] = {"peel.depth", "peel.id", "peel.shade"};
  return hairPass(names[step], first)
      .storage(AccumComposite::kAccumBinding, composite_.accum())
      .storage(kState, state_)
      .storage(kPeeled, peeled_);
}

Pass PeelOit::advancePass() const {
  return Pass("peel.advance")
      .uniform(kSize, sizeUbo_)
      .storage(kState, state_)
      .storage(kPeeled, peeled_);
}

void PeelOit::addPasses(FrameGraph& graph, Device& dev) {
  // The first draw clears the depth when nothing opaque was drawn.
  const std::vector<Pass> steps = {stepPass(0, true), stepPass(0, false), stepPass(1, false),
                                   stepPass(2, false)};
  const Pass advance = advancePass(), composite = composite_.pass();
  graph.add("peel", {steps[0], steps[2], steps[3], advance, composite},
            [this, &dev, steps, advance] {
              dev.fillBuffer(composite_.accum(), 0);
              dev.fillBuffer(peeled_, 0);
              dev.fillBuffer(state_, 0xFFFFFFFFu);
              for (uint32_t layer = 0; layer < layers_; ++layer) {
                steps[layer == 0 ? 0 : 1].draw(dev, step_[0], hairVertices());
                steps[2].draw(dev, step_[1], hairVertices());
                steps[3].draw(dev, step_[2], hairVertices());
                const glm::uvec2 g = dispatchGroups(pixels());
                advance.dispatch(dev, advance_, g.x, g.y);
              }
              if (layers_ == 0 && !targets_.opaqueDrawn)  // no layer: still clear the depth
                steps[0].draw(dev, Pipeline{}, 0);
              composite_.record(dev);
            });
}

std::vector<std::string> PeelOit::warnings(Device&) {
  if (layers_ < complexity_.max)
    return {"depth peeling capped at " + std::to_string(layers_) + " of " +
            std::to_string(complexity_.max) + " layers (option layers=)"};
  return {};
}

}  // namespace sb
