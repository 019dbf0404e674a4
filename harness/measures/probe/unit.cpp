// The probe measure (probe.h): the technique's visibility at the probe points, read from the
// measurement frame, beside the exact reference's.
#include "harness/measures/measure_unit.h"
#include "harness/measures/probe/probe.h"
#include "render/frame/renderer.h"

namespace sb {
namespace {

std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  if (!in.req.probe || !in.reference) return nullptr;
  auto p = std::make_shared<ProbeResult>();
  p->texel = in.req.probe->texel;
  p->mapSize = in.req.probe->mapSize;
  p->lightDepth = in.probeDepths;
  p->exact = in.reference->probe;
  p->visibility = in.renderer.readProbe();
  return p;
}

}  // namespace

void ProbeResult::json(nlohmann::json& report) const {
  report["probe"] = {{"texel", {texel.x, texel.y}},
                     {"map_size", mapSize},
                     {"light_depth", lightDepth},
                     {"exact", exact},
                     {"visibility", visibility}};
}

}  // namespace sb

SB_MEASURE({.name = "probe",
            .help = "with --probe: visibility along one light ray, the technique's and the "
                    "exact reference's",
            .measure = sb::measure});
