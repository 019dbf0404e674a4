// The exact reference of a render (harness/render_steps.h) and the visibility error against
// it; what is measured beyond that are the measure units (harness/measures/).
#include "backends/device.h"
#include "harness/measures/measure_unit.h"
#include "harness/render_steps.h"
#include "imaging/metrics.h"
#include "render/frame/renderer.h"
#include "render/graph/frame_planner.h"

namespace sb {

VisibilityError visibilityError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  return compareVisibility(visibilityFloats(a), visibilityFloats(b));
}

RenderCache::Reference renderReference(Device& dev, const Scene& scene,
                                       const RenderSettings& settings, const Spec& refShadow,
                                       const RenderRequest& req) {
  Outputs outputs = {Output::Visibility};
  if (req.image) outputs.insert(Output::Color);
  if (req.probe) outputs.insert(Output::Probe);
  // The reference is exact at each pixel's centre: one sample, whatever
  // --msaa the run has (its error then includes what anti-aliasing changed).
  RenderSettings exactSettings = settings;
  exactSettings.msaa = 1;
  Renderer ref(dev, scene, exactSettings, refShadow, Spec::parse(kReferenceOit), outputs);
  checkMemory(FramePlanner::of(dev).allocationsAfterUsing(ref.graphResources(outputs)),
              dev.allocations(), 0, dev.memoryBudget(), "the reference",
              req.image ? imageHostBytes(settings) : 0);
  ref.renderFrame();
  RenderCache::Reference r;
  if (req.image) r.image = colorImage(ref, settings);
  r.visibility = ref.readVisibility();
  if (req.probe) r.probe = ref.readProbe();
  r.eye = ref.oit().depthComplexity();
  r.light = ref.shadow().depthComplexity();
  for (auto& w : ref.warnings()) r.warnings.push_back("reference: " + w);
  return r;
}

}  // namespace sb
