#include "render/outputs/probe/probe.h"

#include <cstring>

#include "render/outputs/probe/slots.h"
#include "render/shading/hair_shading.h"

namespace sb {

namespace {
constexpr uint32_t kPoints = SB_SLOT_PROBE_POINTS, kValues = SB_SLOT_PROBE_VALUES;
}

void ProbeOutput::setup(Device& dev, const std::vector<glm::vec3>& points,
                        const HairShading& shading) {
  shading_ = &shading;
  count_ = uint32_t(points.size());
  std::vector<glm::vec4> p;
  for (const auto& x : points) p.emplace_back(x, 1.0f);
  points_ = dev.createBuffer(
      {"probe.points", Owner::Frame, BufferUsage::Storage, p.size() * sizeof(glm::vec4)}, p.data());
  values_ = dev.createBuffer({"probe.values", Owner::Frame, BufferUsage::Storage, p.size() * 4});
  const ShaderCode comp = loadShader("render/outputs/probe/probe.comp", shading.hairDefines());
  PipelineDesc d = pass().pipeline(dev, "probe", "probe+" + shading.shadow().name());
  d.compute = &comp;
  pipeline_ = dev.createPipeline(d);
}

Pass ProbeOutput::pass() const {
  return Pass("probe")
      .inputs(shading_->shadow().lookup().inputs)
      .readStorage(kPoints, points_)
      .storage(kValues, values_);
}

void ProbeOutput::addPasses(FrameGraph& graph, Device& dev) {
  graph.add(pass(), [this, &dev, p = pass()] {
    const glm::uvec2 g = dispatchGroups(count_);
    p.dispatch(dev, pipeline_, g.x, g.y);
  });
}

std::vector<float> ProbeOutput::read(Device& dev) const {
  const auto bytes = dev.readBuffer(values_);
  std::vector<float> v(count_);
  std::memcpy(v.data(), bytes.data(), v.size() * 4);
  return v;
}

}  // namespace sb
