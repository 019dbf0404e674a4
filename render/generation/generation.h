// The scene's strands made on the device from its groom (render --geometry
// compute; scenes/groom.h, docs/geometry.md): a compute pass runs the rule of
// scenes/groom_rule.h, the one the CPU ran to make Scene::strands, into the
// buffers every technique reads, laid out as the CPU path uploads them, so
// that every technique works on it unchanged and sees the same strands.
#pragma once

#include "render/common/technique.h"

namespace sb {

// Why `geometry` (render --geometry: cpu, compute or mesh) cannot make this
// scene's strands, or "" when it can.
std::string geometryRefusal(const std::string& geometry, const Scene& scene);

class StrandGeneration {
 public:
  // Declares the pass's inputs (the guides, neighbours and placements, owner
  // "scene") and the output buffers of `gpu` (points, colours and segments),
  // made and filled by run(). Throws InputError for a scene without a groom.
  void setup(Device& dev, const Scene& scene, GpuScene& gpu);
  // Runs the pass in a frame of its own (once: the groom does not move).
  void run(Device& dev);

 private:
  Buffer params_, guidePoints_, guideColors_, neighbours_, placements_, seeds_, lods_, guideOrder_;
  Buffer points_, colors_, segments_;
  Pipeline pipeline_;
  uint32_t total_ = 0;
};

}  // namespace sb
