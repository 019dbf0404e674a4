#pragma once

#include "render/common/technique.h"

namespace sb {

class HairShading;

// Output "probe": the shadow technique's visibility at a list of world points
// (a compute pass including the technique's lookup), read back as floats.
class ProbeOutput {
 public:
  void setup(Device& dev, const std::vector<glm::vec3>& points, const HairShading& shading);
  void addPasses(FrameGraph& graph, Device& dev);
  std::vector<float> read(Device& dev) const;
  Buffer values() const { return values_; }  // the graph output

 private:
  Pass pass() const;

  const HairShading* shading_ = nullptr;
  uint32_t count_ = 0;
  Buffer points_, values_;
  Pipeline pipeline_;
};

}  // namespace sb
