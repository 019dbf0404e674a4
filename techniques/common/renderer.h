// Puts a frame together: the scene on the device, the shadow technique's
// passes, the opaque mesh, the transparency technique and the optional
// visibility and probe outputs, as a frame graph culled to the requested
// outputs ("color", "visibility", "probe"). Runs frames and reads back the images.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "techniques/common/technique.h"
#include "techniques/kajiya_kay/shading.h"
#include "techniques/probe/probe.h"
#include "techniques/visibility/visibility.h"

namespace sb {

struct PassTime {
  std::string name;
  double ms = 0;  // summed over every execution of the pass in the frame
  int executions = 0;
};

class Renderer {
 public:
  Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
           std::unique_ptr<ShadowTechnique> shadow, std::unique_ptr<OitTechnique> oit,
           const std::set<std::string>& outputs = {"color"});
  // The graph nodes that run, in order (those no output needs are left out).
  std::vector<std::string> graphPasses() const;
  // Records and runs one frame; device passes with the same name are summed.
  std::vector<PassTime> renderFrame();
  // One frame for a subset of the constructor's outputs (e.g. only "visibility",
  // to measure an error without shading or timing the measurement).
  std::vector<PassTime> renderFrame(const std::set<std::string>& outputs);
  std::vector<std::string> graphPasses(const std::set<std::string>& outputs) const;
  // The ids of the resources a frame for `outputs` uses (what its kept passes
  // read and write): with Device::allocationsAfterUsing, its memory before it runs.
  std::set<uint32_t> graphResources(const std::set<std::string>& outputs) const;
  // RGBA32F, rows bottom-up (row 0 = NDC y=-1).
  std::vector<uint8_t> readColor();
  // The texture readColor reads (to show it in a window: Device::present).
  Texture colorTexture() const { return color_; }
  // R32F, rows bottom-up; -1 where no surface.
  std::vector<uint8_t> readVisibility();
  // The shadow technique's visibility at settings.probePoints ("probe" output).
  std::vector<float> readProbe();
  const GpuScene& gpuScene() const { return gpu_; }
  ShadowTechnique& shadow() { return *shadow_; }
  OitTechnique& oit() { return *oit_; }
  std::vector<std::string> warnings();
  // The shadow technique's counters, then the transparency technique's.
  std::vector<Counter> counters() {
    std::vector<Counter> all = shadow_->counters(dev_);
    for (Counter& c : oit_->counters(dev_)) all.push_back(std::move(c));
    return all;
  }

 private:
  void upload(const Scene& scene);
  // The graph resources behind the outputs "color", "visibility" and "probe".
  std::vector<GraphResource> resources(const std::set<std::string>& outputs) const;
  std::vector<PassTime> run(const std::vector<const PassNode*>& passes);

  Device& dev_;
  RenderSettings settings_;
  GpuScene gpu_;
  std::unique_ptr<ShadowTechnique> shadow_;
  std::unique_ptr<OitTechnique> oit_;
  KajiyaKayShading shading_;
  VisibilityOutput visibility_;
  ProbeOutput probe_;
  bool wantVisibility_ = false, wantProbe_ = false;
  Texture color_, depth_;
  FrameGraph graph_;
  std::vector<const PassNode*> passes_;
};

}  // namespace sb
