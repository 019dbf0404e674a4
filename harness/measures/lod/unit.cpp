// The level-of-detail measure (lod.h).
#include <algorithm>

#include "harness/measures/lod/lod.h"
#include "harness/measures/measure_unit.h"

namespace sb {
namespace {

std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  if (!in.full.groom.hasLod()) return nullptr;
  const Groom& g = in.scene.groom;
  auto lod = std::make_shared<LevelOfDetail>();
  lod->by = g.lodPixels > 0 ? "lod_pixels" : "lod";
  lod->setting = g.lodPixels > 0 ? g.lodPixels : g.lod;
  lod->strandsFull = g.fullStrands();
  lod->strandsDrawn = g.totalStrands();
  for (const GroomInstanceLod& l : g.lods) lod->shares.push_back(double(l.kept) / g.strands);
  if (in.req.reference && in.req.image && in.reference)
    lod->fullModelError = compareImages(in.out.image, in.fullModelReference()->image);
  return lod;
}

}  // namespace

void LevelOfDetail::json(nlohmann::json& report) const {
  double lo = 1, hi = 0, sum = 0;
  for (double s : shares) {
    lo = std::min(lo, s);
    hi = std::max(hi, s);
    sum += s;
  }
  report["lod"] = {{"by", by},
                   {by, setting},
                   {"strands", strandsDrawn},
                   {"strands_full", strandsFull},
                   {"share", {{"min", lo}, {"mean", sum / double(shares.size())}, {"max", hi}}}};
  if (shares.size() <= 100) report["lod"]["instances"] = shares;
}

void LevelOfDetail::errorJson(nlohmann::json& error) const {
  if (fullModelError) error["full_model"]["image"] = toJson(*fullModelError);
}

}  // namespace sb

SB_MEASURE({.name = "lod",
            .help = "with a level of detail: the strands each instance kept, and the image's "
                    "error against the full model's exact reference (error.full_model)",
            .measure = sb::measure});
