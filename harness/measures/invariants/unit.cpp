// The invariants measure (invariants.h). It runs last: it checks what the other measures
// reported (the errors) as well as the run's image, visibility, probe and maps.
#include <cmath>

#include "backends/device.h"
#include "harness/measures/invariants/invariants.h"
#include "harness/measures/measure_unit.h"
#include "harness/measures/probe/probe.h"
#include "harness/render_steps.h"
#include "render/frame/renderer.h"

namespace sb {
namespace {

std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  if (!in.req.invariants || !in.reference) return nullptr;
  const RenderRequest& req = in.req;
  const RenderResult& out = in.out;
  auto result = std::make_shared<InvariantsResult>();
  std::vector<InvariantFailure>& failures = result->failures;
  if (req.image) {
    const std::string last = out.graph.empty() ? "" : out.graph.back();
    checkColor(out.image, HairShading::maxRadiance(in.settings), last, failures);
  }
  if (req.reference) {
    checkVisibility(out.visibility, "visibility", failures);
    const nlohmann::json errors = errorJson(out);  // named: items() of a temporary dangles
    for (const auto& [kind, e] : errors.items())
      for (const auto& [metric, v] : e.items())
        // PSNR is infinite (null) exactly when the images are identical.
        if (kind != "own" && kind != "by_eye_layers" &&  // copies and objects, checked apart
            ((v.is_null() && !(metric == "psnr" && e.value("identical", false))) ||
             (v.is_number_float() && !std::isfinite(v.get<double>()))))
          failures.push_back({"reference", "error " + kind + "." + metric + " is not a number"});
    if (out.flip && !(out.flip->min >= 0.0 && out.flip->max <= 1.0))
      failures.push_back({"reference", "error image.flip outside [0, 1]"});
  }
  if (const ProbeResult* probe = out.measure<ProbeResult>()) {
    checkRay(probe->visibility, "probe (" + Spec::parse(req.shadow).name + ")", failures,
             in.renderer.shadow().monotone());
    checkRay(in.reference->probe, "probe (reference)", failures);
  }
  for (Texture t : in.renderer.shadow().lookup().inputs.sampled()) {
    const TextureDesc d = in.dev.describe(t);
    checkMap(in.dev.readTexture(t), d.format, "map " + d.name, failures);
  }
  return result;
}

}  // namespace

void InvariantsResult::json(nlohmann::json& report) const {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : failures) list.push_back({{"pass", f.pass}, {"what", f.what}});
  report["invariants"] = {{"failures", list}};
}

void addInvariantFailure(RenderResult& r, InvariantFailure f) {
  auto next = std::make_shared<InvariantsResult>();
  if (const InvariantsResult* now = r.measure<InvariantsResult>()) *next = *now;
  next->failures.push_back(std::move(f));
  r.setMeasure<InvariantsResult>(next);
}

}  // namespace sb

SB_MEASURE({.name = "invariants",
            .help = "with --invariants: the colour, visibility, probe and map checks of "
                    "harness/invariants.h, and every reported error a number",
            .order = 100,
            .measure = sb::measure});
