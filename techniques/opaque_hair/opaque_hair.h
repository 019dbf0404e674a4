#pragma once

#include "render/common/hair_oit.h"
#include "render/common/technique.h"

namespace sb {

// No transparency (--oit none): hair drawn opaque with depth test and write,
// the baseline the papers quote frame rates against.
class OpaqueHair : public KeptInputsOit {
 public:
  std::string name() const override { return "none"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;

 private:
  Pass pass() const;

  Pipeline pipeline_;
};

}  // namespace sb
