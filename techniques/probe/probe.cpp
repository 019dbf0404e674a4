#include "techniques/probe/probe.h"

#include <cstring>

#include "techniques/kajiya_kay/shading.h"

namespace sb {

namespace {
constexpr uint32_t kPoints = SB_SLOT_PROBE_POINTS, kValues = SB_SLOT_PROBE_VALUES;
}

void ProbeOutput::setup(Device& dev, const std::vector<glm::vec3>& points,
                        const KajiyaKayShading& shading) {
  shading_ = &shading;
  count_ = uint32_t(points.size());
  std::vector<glm::vec4> p;
  for (const auto& x : points) p.emplace_back(x, 1.0f);
  points_ = dev.createBuffer(
      {"probe.points", "frame", BufferUsage::Storage, p.size() * sizeof(glm::vec4)}, p.data());
  values_ = dev.createBuffer({"probe.values", "frame", BufferUsage::Storage, p.size() * 4});
  const ShaderCode comp = loadShader("techniques/probe/probe.comp", shading.hairDefines());
  PipelineDesc d;
  d.name = "probe";
  d.technique = "probe+" + shading.shadow().name();
  d.compute = &comp;
  d.bindings = shading.shadow().lookupSlots();
  d.bindings.push_back({kPoints, BindingKind::StorageBuffer});
  d.bindings.push_back({kValues, BindingKind::StorageBuffer});
  pipeline_ = dev.createPipeline(d);
}

void ProbeOutput::addPasses(FrameGraph& graph, Device& dev) {
  graph.add({"probe", shading_->shadowReads(), {"probe"}, [this, &dev] {
               auto b = shading_->shadow().lookupBindings();
               b.push_back(Binding::buf(kPoints, points_));
               b.push_back(Binding::buf(kValues, values_));
               const glm::uvec2 g = dispatchGroups(count_);
               dev.dispatch("probe", pipeline_, b, g.x, g.y);
             }});
}

std::vector<float> ProbeOutput::read(Device& dev) const {
  const auto bytes = dev.readBuffer(values_);
  std::vector<float> v(count_);
  std::memcpy(v.data(), bytes.data(), v.size() * 4);
  return v;
}

}  // namespace sb
