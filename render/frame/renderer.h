// Puts a frame together: the scene on the device, the shadow technique's
// passes, the opaque mesh, the transparency technique and the optional
// visibility and probe outputs, as a frame graph culled to the requested
// outputs (Output: color, visibility, probe). Runs frames and reads back the images.
//
// Several lights (RenderSettings::extraLights) are drawn as multipass lighting:
// each extra light gets its own shadow technique, shading and transparency
// technique, drawn into its own colour with no ambient term and a black
// background, and pass "lights.sum" adds those colours into the key light's.
// Every transparency technique composites linearly in the hair's colour, so
// the sum is the image of all lights at once; the camera-side passes run once
// per light, which is the cost of this way of lighting, not of the shadow
// technique. An extra light's passes and resources are named with its prefix
// ("light2.osm.map"), so their times and memory stand apart.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "render/common/technique.h"
#include "render/frame/output.h"
#include "render/generation/generation.h"
#include "render/outputs/probe/probe.h"
#include "render/outputs/visibility/visibility.h"
#include "render/shading/hair_shading.h"

namespace sb {

struct PassTime {
  std::string name;
  // Whose pass it is: the shadow technique's (Shadow), the transparency
  // technique's (Oit), or the frame's (Frame: shading, outputs, the lights' sum).
  Owner owner = Owner::None;
  double ms = 0;  // summed over every execution of the pass in the frame
  int executions = 0;
  PassWork work;  // likewise summed
};

class Renderer {
 public:
  // One light: settings.extraLights must be empty.
  Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
           std::unique_ptr<ShadowTechnique> shadow, std::unique_ptr<OitTechnique> oit,
           const Outputs& outputs = {Output::Color});
  // Any number of lights: the techniques are made from their specs once per light.
  Renderer(Device& dev, const Scene& scene, const RenderSettings& settings, const Spec& shadow,
           const Spec& oit, const Outputs& outputs = {Output::Color});
  // The names of light i's passes and resources begin with this: "" for the
  // key light (i = 0), "light2." for the first extra light, and so on.
  static std::string lightPrefix(std::size_t i);
  std::size_t lightCount() const { return lights_.size(); }
  // The graph nodes that run, in order (those no output needs are left out).
  std::vector<std::string> graphPasses() const;
  // Records and runs one frame; device passes with the same name are summed.
  std::vector<PassTime> renderFrame();
  // One frame for a subset of the constructor's outputs (e.g. only Output::Visibility,
  // to measure an error without shading or timing the measurement).
  std::vector<PassTime> renderFrame(const Outputs& outputs);
  std::vector<std::string> graphPasses(const Outputs& outputs) const;
  // The ids of the resources a frame for `outputs` uses (what its kept passes
  // read and write): with FramePlanner::allocationsAfterUsing, its memory before it runs.
  std::set<uint32_t> graphResources(const Outputs& outputs) const;
  // RGBA32F, rows bottom-up (row 0 = NDC y=-1).
  std::vector<uint8_t> readColor();
  // The texture readColor reads (to show it in a window: Device::present).
  Texture colorTexture() const { return color_; }
  // R32F, rows bottom-up; -1 where no surface.
  std::vector<uint8_t> readVisibility();
  // The shadow technique's visibility at settings.probePoints (Output::Probe).
  std::vector<float> readProbe();
  const GpuScene& gpuScene() const { return gpu_; }
  // What building the frame ran (render --json "build"): the pipelines
  // compiled (name, technique) and the preparations, only those of techniques
  // whose passes the frame graph kept.
  std::vector<std::pair<std::string, std::string>> compiledPipelines() const {
    return dev_.compiledPipelines(group_.id());
  }
  const std::vector<std::string>& preparations() const { return preparations_; }
  // The key light's techniques.
  ShadowTechnique& shadow() { return *lights_[0]->shadow; }
  OitTechnique& oit() { return *lights_[0]->oit; }
  // Every light's (an extra light's with "light N: " before them).
  std::vector<std::string> warnings();
  // Per light, the shadow technique's counters, then the transparency
  // technique's (an extra light's names with its prefix).
  std::vector<Counter> counters();

 private:
  // What one part of a light (its shadow technique, shading, transparency
  // technique, or its visibility and probe outputs) adds to the frame: graph
  // nodes [firstNode, endNode) and the pipelines it declared. Built (its
  // pipelines compiled, its preparation run) only when a node of it is kept.
  struct Unit {
    enum class Kind { Shadow, Shading, Oit, Measures } kind;
    std::size_t firstNode = 0, endNode = 0;
    std::set<uint32_t> pipelines;
  };
  // One light's share of the frame.
  struct LightChain {
    RenderSettings settings;  // the light's: its light, and for an extra one no ambient, black
    std::unique_ptr<ShadowTechnique> shadow;
    std::unique_ptr<OitTechnique> oit;
    HairShading shading;
    Texture color;            // where it composites: the frame's (key light) or its own
    std::size_t endNode = 0;  // its graph nodes end here (they start where the previous end)
    std::vector<Unit> units;
    std::set<uint32_t> shadowIds, oitIds;  // what each technique declared (the memory guard's)
  };
  struct Techniques {
    std::unique_ptr<ShadowTechnique> shadow;
    std::unique_ptr<OitTechnique> oit;
  };
  Renderer(Device& dev, const Scene& scene, const RenderSettings& settings,
           std::vector<Techniques> techniques, const Outputs& outputs);
  static std::vector<Techniques> one(std::unique_ptr<ShadowTechnique> shadow,
                                     std::unique_ptr<OitTechnique> oit,
                                     const RenderSettings& settings);
  static std::vector<Techniques> perLight(const Spec& shadow, const Spec& oit,
                                          const RenderSettings& settings);
  // Declares a light's resources, pipelines (not compiled) and graph nodes;
  // after the graph is culled, builds what it kept.
  void declareLight(LightChain& light, std::size_t index);
  void buildLight(LightChain& light, std::size_t index);
  bool kept(const Unit& unit) const;
  Owner ownerOf(std::size_t node) const;
  void guardPlan(const Outputs& outputs) const;
  void addSumPass();
  void upload(const Scene& scene);
  // The graph resources behind the outputs.
  std::vector<GraphResource> resources(const Outputs& outputs) const;
  std::vector<PassTime> run(const std::vector<const PassNode*>& passes);

 public:
  // The last frame's passes as the device timed them, each execution apart, with its
  // start in the frame (a trace's slices).
  const std::vector<PassTiming>& lastTimings() const { return lastTimings_; }

 private:
  std::vector<PassTiming> lastTimings_;

  Device& dev_;
  // Everything the renderer and its techniques create on the device, freed
  // with it (declared before what uses those resources, so it goes last).
  ResourceGroup group_;
  RenderSettings settings_;
  GpuScene gpu_;
  StrandGeneration generation_;  // --geometry compute: the strands made on the device
  std::vector<std::unique_ptr<LightChain>> lights_;  // the key light first
  Pipeline sumPipeline_;
  VisibilityOutput visibility_;
  ProbeOutput probe_;
  bool wantVisibility_ = false, wantProbe_ = false;
  Texture color_, depth_;
  FrameGraph graph_;
  std::vector<const PassNode*> passes_;
  std::vector<std::string> preparations_;
};

}  // namespace sb
