#include "techniques/mlab/mlab.h"

namespace sb {

void MlabOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                    const HairShading& shading, const OitTargets& targets) {
  ABufferOit::setup(dev, scene, s, shading, targets);
  // No interlock path is written (it could not run here): with or without the
  // extension the merge runs in the resolve, in primitive order.
  emulated_ = std::string("mlab merges in a resolve pass, in primitive order (device ") +
              (dev.info().fragmentShaderInterlock
                   ? "has fragment-shader interlock; the interlock path is not written)"
                   : "has no fragment-shader interlock)");
}

ShaderDefines MlabOit::resolveDefines() const {
  ShaderDefines d;
  d.defines.push_back({"SB_MLAB_LAYERS", std::to_string(layers_)});
  return d;
}

std::vector<Counter> MlabOit::counters(Device& dev) {
  return {{"emulated_steps", double(status(dev)[2])}};
}

}  // namespace sb
